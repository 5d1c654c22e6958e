# Sourced by the tests that run through Slurm (tests/sweep/slurm.sh,
# tests/rtl/bench_chip_slurm.sh): start_slurm_cluster WORKDIR empties WORKDIR,
# starts a single-node cluster in WORKDIR/cluster (scripts/slurm-cluster),
# stops it when the script exits, and exports SLURM_CONF. If the cluster
# cannot start, the test fails with why.
start_slurm_cluster() {
  local work=$1 root
  root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
  rm -rf "$work"; mkdir -p "$work"
  SLURM_CLUSTER_DIR=$work/cluster
  SLURM_CLUSTER_SCRIPT=$root/scripts/slurm-cluster
  trap '"$SLURM_CLUSTER_SCRIPT" stop "$SLURM_CLUSTER_DIR"' EXIT
  if ! "$SLURM_CLUSTER_SCRIPT" start "$SLURM_CLUSTER_DIR" >"$work/cluster.out" 2>&1; then
    cat "$work/cluster.out"
    echo "FAIL: the Slurm cluster did not start (above); the Slurm executor is untested"
    exit 1
  fi
  export SLURM_CONF=$SLURM_CLUSTER_DIR/slurm.conf
}

# A Slurm test's start, for tests called as `test.sh BUILD WORKDIR`: sets
# `build`, `work` and `root` (the source tree) and starts the cluster in WORKDIR.
begin_slurm_test() {
  build=$1; work=$2
  root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
  start_slurm_cluster "$work"
}
