#!/usr/bin/env bash
# scripts/silicon-activity on a small Whitted run (builtin:spd-tetra through the
# grid unit, Verilated): one waveform a job, summed by lancer_fst_activity into
# toggle rates (the clock toggles twice a cycle; registers move); and the tool
# refuses a file that is not an FST, naming it.
# Usage: check_activity.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src=$1 tree=$2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$src/scripts/silicon-activity" --tree "$tree" --scene builtin:spd-tetra --accel grid --size 4 --out "$out/a.json"
python3 - "$out/a.json" <<'PY'
import json, sys
a = json.load(open(sys.argv[1]))
assert a["cycles"] > 100, a["cycles"]
assert a["waves"] > 1, a["waves"]  # an effects run: a waveform a job
clk = a["signals"]["rt_grid.clk_i"]
assert abs(clk["per_bit_per_cycle"] - 2.0) < 0.01, clk
moving = [k for k, v in a["signals"].items() if k.endswith("_q") and v["per_bit_per_cycle"] > 0]
assert len(moving) > 20, moving
assert "spd-tetra" in a["workload"]
print("activity ok:", a["cycles"], "cycles,", a["waves"], "waveforms,", len(moving), "moving registers")
PY
echo "not a waveform" >"$out/bad.fst"
if "$tree/rtl/lancer_fst_activity" "$out/bad.fst" 2>"$out/err"; then echo "FAIL: a bad FST passed"; exit 1; fi
grep -q "bad.fst: not an FST waveform" "$out/err" || { cat "$out/err"; exit 1; }
echo "refusal ok"
