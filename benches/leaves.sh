#!/usr/bin/env bash
# Leaves in meshes (issue 33), side by side in one run, interleaved run by
# run so machine noise hits each alike; medians of RUNS runs (default 3)
# of wall and user seconds and peak RSS from GNU time (`/usr/bin/time -v`):
#
#   - the leafy oak (examples/oak3d.od) to .glb beside the bare oak
#     (examples/oak3d-bare.od): the target is within 2x its time;
#   - 10^5 leaves in a mesh (benches/leaves/many-leaves.lsys, 131,071
#     leaves): the target is under 1 s;
#   - `--solid` of the leafy oak: under 30 s CPU and 2 GB; the solid is
#     then read by benches/stl_check.py (watertight, one body).
#
#   cargo build --release && benches/leaves.sh [STLC]
#
# Results go into docs/performance.md and docs/3d.md by hand.
set -euo pipefail
cd "$(dirname "$0")/.."
STLC=${1:-target/release/stlc}
RUNS=${RUNS:-3}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
field() { sed -n "s/^[[:space:]]*$1: //p" "$2"; }
declare -A wall user rss
cases="bare leafy many solid"
for i in $(seq "$RUNS"); do
    for c in $cases; do
        case $c in
            bare) args=(examples/oak3d-bare.od -o "$out/bare.glb") ;;
            leafy) args=(examples/oak3d.od -o "$out/leafy.glb") ;;
            many) args=(benches/leaves/many-leaves.lsys -o "$out/many.glb") ;;
            solid) args=(examples/oak3d.od --solid -o "$out/oak.stl") ;;
        esac
        /usr/bin/time -v -o "$out/time" "$STLC" render -q "${args[@]}"
        wall[$c]+="$(field 'Elapsed (wall clock) time (h:mm:ss or m:ss)' "$out/time" | awk -F: '{print $(NF-1)*60+$NF}') "
        user[$c]+="$(field 'User time (seconds)' "$out/time") "
        rss[$c]+="$(field 'Maximum resident set size (kbytes)' "$out/time") "
    done
done
for c in $cases; do
    w=$(tr ' ' '\n' <<<"${wall[$c]}" | grep . | median)
    u=$(tr ' ' '\n' <<<"${user[$c]}" | grep . | median)
    r=$(tr ' ' '\n' <<<"${rss[$c]}" | grep . | median)
    echo "$c: median of $RUNS: wall ${w} s, user ${u} s, peak RSS $((r / 1024)) MiB (walls: ${wall[$c]})"
done
python3 benches/stl_check.py "$out/oak.stl"
