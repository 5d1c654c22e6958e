#!/usr/bin/env bash
# The chip study's Slurm executor for real: a single-node Slurm cluster on this
# machine (scripts/slurm-cluster, in WORKDIR), scripts/bench-chip --short as a
# job array and a merge job, and its merged rows equal the local executor's
# (every column but the host's seconds). If the cluster cannot start, the
# test fails with why.
# Usage: bench_chip_slurm.sh BUILD WORKDIR
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../support/slurm_cluster.sh"
begin_slurm_test "$@"
"$root/scripts/bench-chip" --short --build "$build" --out "$work/local"
"$root/scripts/bench-chip" --short --build "$build" --out "$work/slurm" --executor slurm --wait
/usr/bin/python3 - "$work/local/chip.csv" "$work/slurm/chip.csv" <<'PY'
import csv, sys
a, b = ([{k: v for k, v in r.items() if k != "host_seconds"} for r in csv.DictReader(open(f))] for f in sys.argv[1:])
assert a and a == b, "the local and Slurm rows differ"
print(f"ok: {len(a)} rows equal between the local and Slurm executors")
PY
