#!/usr/bin/env bash
# The sweep's plots: scripts/sweep-plot on a fixed sweep.csv (tests/data/sweep-small.csv:
# 8/8, 16/16 and 24/24, isect with synthesis figures and grid without, the scenes'
# sum and the Cornell box; 24/24 misclassified nothing), its errors, and a small
# `lancer sweep` that draws its own plots.
# Usage: plots.sh LANCER TREE WIDTH SOURCE WORKDIR   (TREE is a built tree of WIDTH)
set -uo pipefail
lancer=$1; tree=$2; width=$3; src=$4; work=$5
rm -rf "$work"; mkdir -p "$work/fixed" "$work/empty" "$work/narrow"
source "$(dirname "$0")/check.sh"
plot=$src/scripts/sweep-plot
is_png() { [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] && [ "$(stat -c %s "$1")" -gt 10000 ]; }

# Three curves against width (isect per scene and summed, grid summed) and one
# against cost (grid has no area); each curve's 24/24 point drawn hollow.
cp "$src/tests/data/sweep-small.csv" "$work/fixed/sweep.csv"
check fixed 0 "accuracy_vs_cost.png \(4 curves, 4 points with none misclassified drawn hollow\)" -- "$plot" "$work/fixed"
for f in misclassified_vs_width accuracy_vs_cost; do
  is_png "$work/fixed/$f.png" || fail "fixed: $f.png is not a PNG of the plot"
done

check no-csv 1 "sweep-plot: $work/none/sweep.csv: No such file or directory" -- "$plot" "$work/none"
head -1 "$work/fixed/sweep.csv" >"$work/empty/sweep.csv"
check no-rows 1 "sweep-plot: $work/empty/sweep.csv has no rows" -- "$plot" "$work/empty"
cut -d, -f1-6 "$work/fixed/sweep.csv" >"$work/narrow/sweep.csv"
check no-columns 1 "sweep-plot: $work/narrow/sweep.csv lacks the columns cells_x_ns_per_ray, cycles_per_ray" -- "$plot" "$work/narrow"

# lancer sweep draws both plots itself (no --no-plots): one curve against width, and
# without synthesis one against the RTL's cycles per ray.
check sweep 0 "rows in .*/sweep.csv, 0 jobs without a result" -- \
  "$lancer" sweep --widths "$width" --tree "$width=$tree" --scenes builtin:cornell --image 12 --crack-rays 48 \
  --models golden,rtl -j 2 --out "$work/sweep"
for f in misclassified_vs_width accuracy_vs_cost; do
  is_png "$work/sweep/$f.png" || fail "sweep: no $f.png"
done
grep -q "2 curves" "$work/sweep/plots.log" || fail "sweep: plots.log does not say 2 curves: $(tail -1 "$work/sweep/plots.log")"

finish "sweep plot"
