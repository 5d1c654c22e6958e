#!/usr/bin/env bash
# lancer sweep on bad input: each error names the width or job, exits non-zero,
# keeps the other results; a rerun runs only the jobs without a result.
# Usage: errors.sh LANCER TREE WIDTH WORKDIR   (TREE is a built tree of WIDTH)
set -uo pipefail
lancer=$1; tree=$2; width=$3; work=$4
rm -rf "$work"; mkdir -p "$work"
source "$(dirname "$0")/check.sh"
base=(--tree "$width=$tree" --image 12 --crack-rays 48 --models golden --no-plots -j 2)

check unknown-unit 1 "unknown unit 'bogus'" -- "$lancer" sweep --widths "$width" "${base[@]}" --scenes builtin:cornell --units isect,bogus --out "$work/a"
check width-low 1 "width 3/10: 3 bits lies outside what the formats admit \(4..24\)" -- \
  "$lancer" sweep --widths 3/10 --scenes builtin:cornell --out "$work/a"
check width-high 1 "width 12/25: 25 bits lies outside" -- "$lancer" sweep --widths 12/25 --scenes builtin:cornell --out "$work/a"
check width-text 1 "width 'x/8' is not P/D" -- "$lancer" sweep --widths x/8 --scenes builtin:cornell --out "$work/a"
check tree-mismatch 4 "width 9/9: tree .* is configured for $width, not 9/9" -- \
  "$lancer" sweep --widths 9/9 --tree "9/9=$tree" --scenes builtin:cornell --models golden --no-plots --out "$work/m"

# A scene that does not load: its jobs fail naming it, the other scene's results are kept.
check bad-scene 4 "scene $work/missing.obj does not load" -- \
  "$lancer" sweep --widths "$width" "${base[@]}" --scenes "builtin:cornell,$work/missing.obj" --chunks 2 --out "$work/s"
grep -q "builtin:cornell" "$work/s/sweep.csv" || fail "bad-scene: the good scene's rows are gone"
grep -q "job w${width/\//-}.isect.golden.s1.c0of2 (width $width, unit isect, model golden, scene $work/missing.obj" \
  "$work/bad-scene.out" || fail "bad-scene: no error naming the job"

# Resume: the good scene's jobs are kept; a removed result is the only job rerun.
check resume-all 0 "3 jobs planned, 3 with results, 0 to run" -- \
  "$lancer" sweep --widths "$width" "${base[@]}" --scenes builtin:cornell --chunks 2 --out "$work/s"
rm "$work/s/jobs/w${width/\//-}.isect.golden.s0.c1of2.json"
check resume-one 0 "3 jobs planned, 2 with results, 1 to run" -- \
  "$lancer" sweep --widths "$width" "${base[@]}" --scenes builtin:cornell --chunks 2 --out "$work/s"
# Cracks: every ray aimed exactly at a shared edge or vertex hits (column "cracks" is 0).
python3 - "$work/s/sweep.csv" <<'PY' || fail "cracks: the crack rows do not hold"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert rows, "no rows"
for r in rows:
    assert r["crack_rays"] and int(r["crack_rays"]) > 0, f"no crack rays in {r}"
    assert r["cracks"] == "0", f"cracks {r['cracks']} at {r['width']}"
    assert int(r["rays"]) == 144 and r["misclassified_fraction"] != "", r
print("ok   cracks: 0 of", rows[0]["crack_rays"])
PY

# The quadric unit (rt_quadric on native spheres and cones): a scene without
# any is an error naming the job; on the sphereflake its row counts quadric
# tests and takes no crack rays.
check quadric-none 4 "unit quadric, model golden, scene builtin:cornell.*no sphere or cone" -- \
  "$lancer" sweep --widths "$width" "${base[@]}" --scenes builtin:cornell --units quadric --out "$work/q0"
check quadric 0 "1 jobs planned" -- \
  "$lancer" sweep --widths "$width" "${base[@]}" --scenes builtin:spd-balls@1 --units quadric --out "$work/q"
python3 - "$work/q/sweep.csv" <<'PY' || fail "quadric: the quadric row does not hold"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 1 and rows[0]["unit"] == "quadric", rows
r = rows[0]
assert float(r["quadric_tests_per_ray"]) > 0, r
assert r["crack_rays"] == "" and r["misclassified_fraction"] != "" and r["arbiter_hw_beyond_bound"] == "0", r
print("ok   quadric row:", r["quadric_tests_per_ray"], "quadric tests a ray")
PY

# A failed build names the width and keeps the other width's results.
check bad-build 4 "width 6/6: configuring .* failed \\(exit 1\\): LANCER_MEM_ADDR_BITS must lie in 10..30" -- \
  "$lancer" sweep --widths "$width,6/6" "${base[@]}" --scenes builtin:cornell --tree-pattern "$work/tree-{pos}-{dir}" \
  --cmake-arg=-DLANCER_MEM_ADDR_BITS=5 --out "$work/b"
grep -q "^$width," "$work/b/sweep.csv" || fail "bad-build: the good width's rows are gone"

# A spec file with an unknown key.
echo '{"widths": ["8/8"], "scenes": ["builtin:cornell"], "colour": 1}' >"$work/spec.json"
check spec-key 1 "spec.json: unknown key 'colour'" -- "$lancer" sweep --spec "$work/spec.json" --out "$work/a"
finish "sweep error"
