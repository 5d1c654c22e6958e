#!/usr/bin/env bash
# The silicon flow's smoke test (docs/silicon.md): a FIFO deep enough for its
# array to be cut out as a memory macro, mapped onto SKY130, linked and timed
# by OpenSTA, with figures in range; then its refusals: a missing liberty file
# and a missing `sta`, each named with how to fix it.
# Usage: check_silicon.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src=$1 tree=$2
silicon=$src/scripts/silicon
python3 "$silicon" --tree "$tree" --top rt_fifo --set Width=40 --set Depth=128 --check-only --remap
python3 - "$tree/silicon/rt_fifo-Width-40-Depth-128/silicon.json" <<'PY'
import json, sys
fig = json.load(open(sys.argv[1]))
macros = fig["macros"]
assert list(macros) == ["mem_q"], macros
m = macros["mem_q"]
assert (m["words"], m["width"]) == (128, 40), m
assert 0.005 < m["model"]["area_mm2"] < 0.2, m
assert fig["logic"]["flip_flops"] < 64, fig["logic"]  # the array is not flip-flops
assert 100 < fig["sta"]["fmax_mhz"] < 2000, fig["sta"]
assert fig["logic"]["area_um2"] > 500, fig["logic"]
assert fig["clock_source"] == "sta sky130_fd_sc_hd tt_025C_1v80"
print("smoke ok:", fig["sta"]["fmax_mhz"], "MHz,", fig["logic"]["area_um2"], "um2 of cells")
PY

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
if LANCER_SILICON_LIBERTY=/nonexistent/lib.gz python3 "$silicon" --tree "$tree" --top rt_fifo --check-only \
    2>"$out/err"; then
  echo "FAIL: a missing liberty file passed"; exit 1
fi
grep -q "no liberty file /nonexistent/lib.gz" "$out/err" || { cat "$out/err"; exit 1; }
mkdir "$out/bin"
ln -s "$(python3 -c "import sys; print(sys.executable)")" "$out/bin/python3"
ln -s "$(command -v yosys)" "$out/bin/yosys"
if PATH=$out/bin "$out/bin/python3" "$silicon" --tree "$tree" --top rt_fifo --check-only 2>"$out/err"; then
  echo "FAIL: a missing sta passed"; exit 1
fi
grep -q 'no `sta` on PATH: install the Debian package opensta' "$out/err" || { cat "$out/err"; exit 1; }
echo "refusals ok"
