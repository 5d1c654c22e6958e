#!/usr/bin/env bash
# Runs one libFuzzer target on its committed corpus (tests/fuzz/CMakeLists.txt, scripts/fuzz).
# Usage: run_fuzz.sh <fuzz binary> <committed corpus dir> <work dir> [libFuzzer flags...]
# New inputs go to <work dir>/corpus (emptied first, so a run is repeatable), crash
# reproducers to <work dir>/ (crash-*, leak-*, timeout-*); exit status non-zero on a finding.
set -euo pipefail
fuzzer=$1 corpus=$2 work=$3
shift 3
rm -rf "$work/corpus"
mkdir -p "$work/corpus"
# The first directory receives new inputs; the committed one is only read.
exec "$fuzzer" -artifact_prefix="$work/" -print_final_stats=1 "$@" "$work/corpus" "$corpus"
