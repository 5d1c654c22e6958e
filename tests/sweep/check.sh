# Sourced by the sweep test scripts: check NAME EXPECTED-STATUS PATTERN -- command...
# runs the command into $work/NAME.out and counts a failure in $fails unless it
# exits EXPECTED-STATUS with PATTERN (an extended regex) in its output;
# fail WHAT counts one more; finish WHAT exits 1 if any failed.
fails=0
check() {
  local name=$1 want=$2 pattern=$3; shift 4
  "$@" >"$work/$name.out" 2>&1; local rc=$?
  if [ "$rc" != "$want" ] || ! grep -qE -- "$pattern" "$work/$name.out"; then
    echo "FAIL $name: exit $rc (want $want), output lacks /$pattern/:"; tail -20 "$work/$name.out"; fails=$((fails + 1))
  else
    echo "ok   $name"
  fi
}
fail() { echo "FAIL $*"; fails=$((fails + 1)); }
finish() {
  [ "$fails" = 0 ] || { echo "$fails checks failed"; exit 1; }
  echo "all $1 checks passed"
}
