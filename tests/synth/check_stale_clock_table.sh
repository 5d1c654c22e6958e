#!/usr/bin/env bash
# scripts/clock-table --check fails, naming the row, on a table whose row was
# measured on other RTL sources (one digit of a sources_sha256 changed).
# Usage: check_stale_clock_table.sh SOURCE_DIR OUTDIR
set -euo pipefail
src=$1 out=$2
python3 - "$src/rtl/synth/clocks.json" "$out/stale-clocks.json" <<'PY'
import json, sys
table = json.load(open(sys.argv[1]))
row = table["units"][0]
row["sources_sha256"] = ("0" if row["sources_sha256"][0] != "0" else "1") + row["sources_sha256"][1:]
json.dump(table, open(sys.argv[2], "w"))
PY
if python3 "$src/scripts/clock-table" --check --table "$out/stale-clocks.json" 2>"$out/stale-clocks.err"; then
  echo "FAIL: --check passed a stale table"; exit 1
fi
cat "$out/stale-clocks.err"
grep -q "measured on other RTL sources than this tree's" "$out/stale-clocks.err"
echo ok
