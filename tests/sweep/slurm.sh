#!/usr/bin/env bash
# The Slurm executor for real: a single-node Slurm cluster on this machine
# (scripts/slurm-cluster, in WORKDIR), a small sweep through it (two widths,
# the golden and RTL models, the Cornell box in chunks, crack rays), and the
# merged results equal the local executor's bit for bit (sweep-exact.csv and
# every job's counts). If the cluster cannot start, the test fails with why.
# Usage: slurm.sh LANCER TREE WIDTH NARROW_TREE WORKDIR
set -euo pipefail
lancer=$1; tree=$2; width=$3; narrow=$4; work=$5
source "$(dirname "${BASH_SOURCE[0]}")/../support/slurm_cluster.sh"
start_slurm_cluster "$work"

widths=$width; trees=(--tree "$width=$tree")
if [ "$width" != 10/10 ]; then widths=10/10,$width; trees+=(--tree "10/10=$narrow"); fi
spec=(--widths "$widths" "${trees[@]}" --scenes builtin:cornell --units isect --models golden,rtl
      --image 24 --chunks 2 --crack-rays 64 --no-plots)
"$lancer" sweep "${spec[@]}" --executor local -j 2 --out "$work/local"
"$lancer" sweep "${spec[@]}" --executor slurm --wait --out "$work/slurm"

cmp "$work/local/sweep-exact.csv" "$work/slurm/sweep-exact.csv"
# Every job's hardware answers and counts (the run reports without host times).
python3 - "$work/local" "$work/slurm" <<'PY'
import json, os, sys
a, b = sys.argv[1:]
host = {"host_seconds", "model_seconds", "golden_seconds"}
jobs = sorted(f for f in os.listdir(f"{a}/jobs") if f.endswith(".json") and not f.endswith(".error.json"))
assert jobs, "no job results"
for f in jobs:
    ra, rb = (json.load(open(f"{d}/jobs/{f}"))["run"] for d in (a, b))
    for k in host:
        ra.pop(k, None); rb.pop(k, None)
    ra.pop("scene", None); rb.pop("scene", None)
    assert ra == rb, f"{f}: local and Slurm results differ"
print(f"ok: {len(jobs)} jobs equal between the local and Slurm executors")
PY
rows=$(($(wc -l <"$work/local/sweep-exact.csv") - 1))
echo "slurm sweep: $rows rows equal bit for bit between the local and Slurm executors"
