#!/usr/bin/env bash
# Byte-identical outputs (issue 32, item 4): renders every example with one
# binary into a directory, or compares two such directories with `cmp`.
#
#   benches/same-bytes.sh run STLC DIR     # every case's output, stderr, exit code
#   benches/same-bytes.sh cmp DIR_A DIR_B  # lists the cases that differ
#
# Cases: every examples/*.lsys and *.od to PNG and SVG at its default depth,
# at a deep depth (its generations + 4, stand-ins everywhere) and 2048 px;
# stochastic systems with a second seed; 3D inputs in two views and as a
# mesh (.glb and .obj); `stats` and `expand` (.lsys).
set -uo pipefail
cd "$(dirname "$0")/.."
mode=$1
if [ "$mode" = cmp ]; then
  a=$2 b=$3 bad=0 n=0
  for f in "$a"/*; do
    n=$((n + 1))
    g="$b/$(basename "$f")"
    if ! cmp -s "$f" "$g"; then echo "DIFFERS: $(basename "$f")"; bad=$((bad + 1)); fi
  done
  echo "$n files compared, $bad differ"
  [ "$bad" -eq 0 ]
  exit
fi
S=$(realpath "$2") D=$3
mkdir -p "$D"
D=$(realpath "$D")
# Run in D with relative output names, so messages naming them agree.
one() { # name, args...
  local name=$1; shift
  (cd "$D" && timeout 300 "$S" "$@" >"$name.stdout" 2>"$name.stderr"; echo $? >"$name.rc")
}
for f in "$PWD"/examples/*.lsys "$PWD"/examples/*.od; do
  b=$(basename "$f")
  gen=$(awk '$1 == "generations" {print $2; exit}' "$f")
  three=0
  grep -qE '^\s*(dimensions 3|tropism|DIMENSIONS)' "$f" && three=1
  case "$b" in abop-2.*|plant3d*|hilbert3d*|forest3d*|oak3d*) three=1 ;; esac
  one "$b.png" render "$f" -o "$b.png"
  one "$b.svg" render "$f" -o "$b.svg"
  one "$b.2048.png" render "$f" --size 2048x2048 -o "$b.2048.png"
  if [ -n "$gen" ]; then
    deep=$((gen + 4))
    one "$b.deep.png" render "$f" --depth "$deep" -o "$b.deep.png"
    one "$b.deep.svg" render "$f" --depth "$deep" -o "$b.deep.svg"
    one "$b.deep2048.png" render "$f" --depth "$deep" --size 2048x2048 -o "$b.deep2048.png"
    one "$b.seed.png" render "$f" --depth "$deep" --seed 7 -o "$b.seed.png"
    one "$b.stats" stats "$f" --json
    one "$b.deepstats" stats "$f" --depth "$deep" --json
    one "$b.expand" expand "$f" -o "$b.expand.txt"
  fi
  if [ "$three" = 1 ]; then
    one "$b.v1.png" render "$f" --view 60,10 -o "$b.v1.png"
    one "$b.v2.svg" render "$f" --view -30,45 -o "$b.v2.svg"
    one "$b.glb" render "$f" -o "$b.glb"
    one "$b.obj" render "$f" -o "$b.obj"
    if [ -n "$gen" ]; then
      one "$b.deepv.png" render "$f" --depth $((gen + 3)) --view 60,10 -o "$b.deepv.png"
    fi
  fi
done
for d in 10 12 20 40; do
  one "1.24a.$d.png" render "$PWD"/examples/abop-1.24a.lsys --depth $d -o "1.24a.$d.png"
  one "1.24a.$d.svg" render "$PWD"/examples/abop-1.24a.lsys --depth $d -o "1.24a.$d.svg"
  one "1.27.$d.png" render "$PWD"/examples/abop-1.27.lsys --depth $d -o "1.27.$d.png"
  one "hilbert.$d.png" render "$PWD"/examples/hilbert.lsys --depth $d -o "hilbert.$d.png"
  one "plant3d.$d.png" render "$PWD"/examples/plant3d-bare.lsys --depth $d -o "plant3d.$d.png"
done
