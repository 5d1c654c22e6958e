#!/usr/bin/env bash
# One regression check (tests/regress/CMakeLists.txt): runs RAYS through MODEL on
# the ACCEL path and requires the hit list to be byte-identical to the committed
# golden list traces/<stem>.pos<P>-dir<D>.csv (or traces/<stem>.<ACCEL>.pos<P>-dir<D>.csv
# where a path has its own). The scene is named in the rays file by a
# "# scene: NAME" comment line.
# Exit 0 pass, 1 fail, 77 skip (no golden list for this build's formats, or the
# path has no such model in this build).
# Usage: check_trace.sh LANCER RAYS ACCEL MODEL POS_BITS DIR_BITS OUT_DIR
set -u
if [ $# -ne 7 ]; then
  echo "usage: check_trace.sh LANCER RAYS ACCEL MODEL POS_BITS DIR_BITS OUT_DIR"; exit 1
fi
lancer=$1 rays=$2 accel=$3 model=$4 pos=$5 dir=$6 out=$7
traces=$(dirname "$rays")
stem=$(basename "$rays" .rays)
# The path's own list if it has one, else the list every path shares.
expected=$traces/$stem.$accel.pos$pos-dir$dir.csv
[ -f "$expected" ] || expected=$traces/$stem.pos$pos-dir$dir.csv

if [ ! -f "$expected" ]; then
  shopt -s nullglob
  others=("$traces/$stem".pos*-dir*.csv "$traces/$stem.$accel".pos*-dir*.csv)
  if ((${#others[@]})); then
    echo "SKIP: the golden hit lists of $stem in traces/ are for other formats ($(basename -a "${others[@]}" | tr '\n' ' '))"
    echo "      and this build uses pos $pos / dir $dir bits; a list is valid only for the formats in its name"
    echo "      (lists for this build: LANCER_BUILD_DIR=<this build> scripts/make-traces <scratch dir>)"
    exit 77
  fi
  echo "FAIL: no golden hit list for $stem (run scripts/make-traces)"; exit 1
fi
scene=$(sed -n 's/^# scene: \([^ ]*\).*/\1/p' "$rays" | head -n 1)
if [ -z "$scene" ]; then
  echo "FAIL: $rays has no '# scene: NAME' line"; exit 1
fi

mkdir -p "$out"
actual=$out/$stem.$accel.$model.csv
log=$out/$stem.$accel.$model.log
rm -f "$actual"
cmd=("$lancer" run --scene "$scene" --rays "$rays" --accel "$accel" --model "$model" --hits "$actual"
     --repro "$out/$stem.$accel.$model.mismatch.rays")
echo "${cmd[*]}"
"${cmd[@]}" >"$log" 2>&1
status=$?
cat "$log"
if [ "$status" -ne 0 ]; then
  if grep -q "has no such model" "$log"; then
    echo "SKIP: the $accel path has no model '$model' in this build"; exit 77
  fi
  echo "FAIL: lancer run exited with status $status"; exit 1
fi
if cmp -s "$expected" "$actual"; then
  echo "ok: $(($(wc -l <"$actual") - 1)) rays, hit list identical to $(basename "$expected")"
  exit 0
fi
echo "FAIL: the hit list differs from the committed golden list"
echo "  expected $expected"
echo "  actual   $actual"
diff "$expected" "$actual" | head -n 20
exit 1
