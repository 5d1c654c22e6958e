#!/usr/bin/env bash
# Frames sharded over Slurm for real: a single-node Slurm cluster on this
# machine (scripts/slurm-cluster, in WORKDIR), scripts/render-shards --short as
# a job array and a merge job, and its frame equals the local executor's and
# the one-machine run's, bit for bit. If the cluster cannot start, the test
# fails with why.
# Usage: render_shards_slurm.sh BUILD WORKDIR
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../support/slurm_cluster.sh"
begin_slurm_test "$@"
"$root/scripts/render-shards" --short --build "$build" --out "$work/local"
"$root/scripts/render-shards" --short --build "$build" --out "$work/slurm" --executor slurm --wait
cmp "$work/local/frame.png" "$work/slurm/frame.png"
/usr/bin/python3 - "$work/local/frame.json" "$work/slurm/frame.json" <<'PY'
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:])
assert a["classes"] == b["classes"] and a["mismatches"] == b["mismatches"] == 0, "the local and Slurm frames differ"
print(f"ok: {a['shards']} shards, the same frame under the local and Slurm executors")
PY
