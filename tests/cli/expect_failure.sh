#!/usr/bin/env bash
# Runs a command that must fail cleanly: the exit status must be EXPECTED (or any
# non-zero status below 128 when EXPECTED is "nonzero"; 128+ means a crash) and
# stderr must match REGEX.
# Usage: expect_failure.sh EXPECTED REGEX -- COMMAND [ARGS...]
set -u
expected=$1 regex=$2
shift 3
stderr=$("$@" 2>&1 >/dev/null)
status=$?
echo "exit status $status; stderr: $stderr"
if [ "$status" -ge 128 ] || [ "$status" -eq 0 ]; then
  echo "FAIL: expected a clean non-zero exit"; exit 1
fi
if [ "$expected" != nonzero ] && [ "$status" -ne "$expected" ]; then
  echo "FAIL: expected exit status $expected"; exit 1
fi
if ! grep -Eq -- "$regex" <<<"$stderr"; then
  echo "FAIL: stderr does not match /$regex/"; exit 1
fi
if [ "$(wc -l <<<"$stderr")" -gt 20 ]; then
  echo "FAIL: the error should be short"; exit 1
fi
echo "ok"
