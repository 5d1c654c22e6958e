#!/usr/bin/env bash
# lancer stress (docs/stability.md) end to end: the short form through every
# path and model of this build passes every check and reports what it promises;
# with --widths, another width's tree runs the same cases into the one report.
# Usage: check_stress.sh LANCER OUT [--widths W1,W2 --tree W2=DIR]
set -euo pipefail
lancer=$1 out=$2; shift 2
mkdir -p "$out"
if [ $# -eq 0 ]; then
  args=(--quick)
else
  # Two widths: the golden model on two cases is enough to show the merge.
  args=(--quick --models golden --cases closed-mesh,axis-planes --work "$out/work" "$@")
fi
"$lancer" stress "${args[@]}" --report "$out/stress.json" > "$out/stress.txt"
python3 - "$out/stress.json" "$out/stress.txt" "$#" <<'PY'
import json, sys
report = json.load(open(sys.argv[1]))
text = open(sys.argv[2]).read()
two_widths = sys.argv[3] != "0"
def fail(why):
    sys.exit(f"FAIL: {why}")
if report["failures"] != 0:
    fail(f"{report['failures']} failed rows")
widths = report["widths"]
if len(widths) != (2 if two_widths else 1):
    fail(f"{len(widths)} widths in the report")
for w in widths:
    rows, placements = w["rows"], w["placements"]
    cases = {p["case"] for p in placements}
    variants = {p["variant"] for p in placements}
    if variants != {"base", "scale 2^-60", "scale 2^60", "translate 1000x", "stretch 10000:1"}:
        fail(f"placements {variants}")
    if not two_widths:
        if len(cases) != 9:
            fail(f"cases {cases}")
        models = {(r["unit"], r["model"]) for r in rows}
        for unit in ("isect", "grid", "octree"):
            if not {"golden", "systemc", "rtl"} <= {m for u, m in models if u == unit}:
                fail(f"the {unit} path should run every model: {models}")
    for r in rows:
        where = f"{w['pos_bits']}/{w['dir_bits']} {r['case']} {r['variant']} {r['unit']} {r['model']}"
        v = r["verdicts"]
        if r["mismatches"] or v["beyond_bound"]:
            fail(f"{where}: {r}")
        if sum(v.values()) != r["rays"] or r["rays"] < 150:
            fail(f"{where}: verdicts {v} for {r['rays']} rays")
        if r["lattice_exact"] and (r["differs_from_base"] or r["cracks"]):
            fail(f"{where}: a power-of-two scale changed an answer or cracked: {r}")
    warned = [p for p in placements if "warning" in p["lattice"]]
    if not any(p["variant"] == "stretch 10000:1" for p in warned):
        fail("a 10^4:1 stretch should warn that the lattice keeps few bits across the scene")
if two_widths and [w["pos_bits"] for w in widths] == [widths[0]["pos_bits"]] * 2:
    fail("the two widths should differ")
for needle in ("per case and placement", "per case, unit and model", "warning:", "stress:"):
    if needle not in text:
        fail(f"the summary should print '{needle}'")
print("ok")
PY
