#!/usr/bin/env bash
# Runs one libFuzzer target on its committed corpus (tests/fuzz/CMakeLists.txt, scripts/fuzz).
# Usage: run_fuzz.sh [--keep] <fuzz binary> <committed corpus dir> <work dir> [libFuzzer flags...]
# New inputs go to <work dir>/corpus, emptied first so that a run is repeatable
# (--keep: kept, so a long run resumes), reproducers of findings to <work dir>/
# (crash-*, leak-*, timeout-*, oom-*); the exit status is non-zero on a finding.
set -euo pipefail
keep=0
if [ "${1:-}" = --keep ]; then keep=1; shift; fi
fuzzer=$1 corpus=$2 work=$3
shift 3
((keep)) || rm -rf "$work/corpus"
mkdir -p "$work/corpus"
# Leaks inside third-party libraries we cannot fix (lsan.supp says which).
export LSAN_OPTIONS="suppressions=$(cd "$(dirname "$0")" && pwd)/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1}"
# The first directory receives new inputs; the committed one is only read.
exec "$fuzzer" -artifact_prefix="$work/" -print_final_stats=1 "$@" "$work/corpus" "$corpus"
