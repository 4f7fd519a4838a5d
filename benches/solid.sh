#!/usr/bin/env bash
# `--solid` of the oak (issue 33: under 30 s and 2 GB), beside the plain
# .glb of the same oak in the same run, interleaved run by run so machine
# noise hits both alike. Medians of RUNS runs (default 3): wall and user
# seconds and peak RSS from GNU time (`/usr/bin/time -v`). Then the same
# solid once as .3mf and once as .glb (`--solid -o oak.3mf`, `-o
# oak-solid.glb`), timed, and all three read by benches/stl_check.py, an
# independent reader (watertight, oriented, one body, volume, Euler
# characteristic; trimesh too where it imports).
#
#   cargo build --release && benches/solid.sh [STLC]
#
# Results go into docs/3d.md (*Solids*) by hand.
set -euo pipefail
STLC=${1:-target/release/stlc}
RUNS=${RUNS:-3}
IN=${IN:-examples/oak3d.od}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
field() { sed -n "s/^[[:space:]]*$1: //p" "$2"; }
declare -A wall user rss
for i in $(seq "$RUNS"); do
    for kind in glb stl; do
        flags=(); [ $kind = stl ] && flags=(--solid)
        /usr/bin/time -v -o "$out/time" "$STLC" render -q "${flags[@]}" -o "$out/oak.$kind" "$IN"
        wall[$kind]+="$(field 'Elapsed (wall clock) time (h:mm:ss or m:ss)' "$out/time" | awk -F: '{print $(NF-1)*60+$NF}') "
        user[$kind]+="$(field 'User time (seconds)' "$out/time") "
        rss[$kind]+="$(field 'Maximum resident set size (kbytes)' "$out/time") "
    done
done
for kind in glb stl; do
    w=$(tr ' ' '\n' <<<"${wall[$kind]}" | grep . | median)
    u=$(tr ' ' '\n' <<<"${user[$kind]}" | grep . | median)
    r=$(tr ' ' '\n' <<<"${rss[$kind]}" | grep . | median)
    echo "$IN -> .$kind: median of $RUNS: wall ${w} s, user ${u} s, peak RSS $((r / 1024)) MiB (walls: ${wall[$kind]})"
done
for file in oak.3mf oak-solid.glb; do
    /usr/bin/time -v -o "$out/time" "$STLC" render -q --solid -o "$out/$file" "$IN"
    w=$(field 'Elapsed (wall clock) time (h:mm:ss or m:ss)' "$out/time" | awk -F: '{print $(NF-1)*60+$NF}')
    echo "$IN -> $file (--solid): one run: wall ${w} s, user $(field 'User time (seconds)' "$out/time") s, peak RSS $(($(field 'Maximum resident set size (kbytes)' "$out/time") / 1024)) MiB, $(stat -c %s "$out/$file") bytes"
done
python3 "$(dirname "$0")/stl_check.py" "$out/oak.stl" "$out/oak.3mf" "$out/oak-solid.glb"
