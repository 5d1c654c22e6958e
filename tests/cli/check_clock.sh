#!/usr/bin/env bash
# lancer run quotes its rates at the STA clock of the slowest unit in the run
# (rtl/synth/clocks.json's silicon figures: SKY130, OpenSTA; docs/silicon.md),
# says so in the summary and the report (clock_source, its model), and an
# explicit --clock-mhz wins and says that it overrides.
# Usage: check_clock.sh LANCER OUTDIR
set -euo pipefail
lancer=$1 out=$2
run() { "$lancer" run --accel grid --model golden --width 8 --height 8 --effects primary "$@"; }

run --report "$out/clock-estimate.json" >"$out/clock-estimate.txt"
grep -E "^  clock +[0-9.]+ MHz, the STA clock of the slowest unit, rt_grid at [0-9]+/[0-9]+ \(sta sky130_fd_sc_hd tt_025C_1v80\)" \
  "$out/clock-estimate.txt"

run --clock-mhz 123 --report "$out/clock-option.json" >"$out/clock-option.txt"
grep -E "^  clock +123 MHz \(--clock-mhz, overriding the estimate of [0-9.]+ MHz for rt_grid at" "$out/clock-option.txt"

python3 - "$out/clock-estimate.json" "$out/clock-option.json" <<'PY'
import json, sys
est, opt = (json.load(open(p)) for p in sys.argv[1:])
src = est["clock_source"]
assert src["kind"] == "estimate", src
assert src["estimate"]["top"] == "rt_grid", src
assert src["model"] == "sta sky130_fd_sc_hd tt_025C_1v80", src
assert est["clock_mhz"] == src["estimate"]["silicon"]["fmax_mhz"] == src["mhz"], est
assert est["clock_mhz"] < src["estimate"]["fmax_mhz"], est  # the gate model's, kept as history, was faster
assert abs(est["clock_hz"] - est["clock_mhz"] * 1e6) < 1, est
assert (src["estimate"]["pos_bits"], src["estimate"]["dir_bits"]) == (est["pos_bits"], est["dir_bits"]), src
assert opt["clock_source"]["kind"] == "option" and opt["clock_mhz"] == 123, opt["clock_source"]
assert opt["clock_source"]["estimate"] == src["estimate"], opt["clock_source"]
print("ok: estimate", src["text"], "| option", opt["clock_source"]["text"])
PY
