#!/usr/bin/env bash
# Space-first growth against bfs and dfs (issue 34, docs/growth.md,
# *Space-first growth: measured*):
#
# 1. Coverage (examples/bench_space.rs): each file grown bfs unbounded,
#    then bfs, dfs and space-first to a third of those stems; the share of
#    the region within 2 L of a stem and the mean distance to the nearest
#    stem, on a grid over the region.
# 2. Cost at scale (examples/bench_grow.rs): N stems (default 10^6) of the
#    benchmark tree (R1 = [-F][F][+F], L=1, B=0.1, 4000 x 4000 rectangle)
#    bfs and space-first, interleaved, RUNS runs (default 3); median growth
#    time and median peak RSS (GNU time -v), and their ratios.
#
#   benches/space.sh [N]
set -euo pipefail
N=${1:-1000000}
RUNS=${RUNS:-3}
cargo build --release --example bench_space --example bench_grow >/dev/null 2>&1
target/release/examples/bench_space examples/2dtree.od examples/holes.od \
  examples/crown.od examples/grove.od benches/space/box-hole.od \
  benches/space/l-shape.od examples/oak3d.od
echo
B=target/release/examples/bench_grow
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
declare -A wall rss
for _ in $(seq "$RUNS"); do
  for order in bfs space; do
    o=$(/usr/bin/time -v "$B" "$order" rstar "$N" 2>&1)
    wall[$order]+="$(sed -n 's/.*time=\([0-9.]*\)s.*/\1/p' <<<"$o") "
    rss[$order]+="$(sed -n 's/.*Maximum resident set size (kbytes): \([0-9]*\).*/\1/p' <<<"$o") "
  done
done
echo "| order | stems | median s (growth) | peak MB |"
echo "| --- | ---: | ---: | ---: |"
for order in bfs space; do
  w=$(tr ' ' '\n' <<<"${wall[$order]}" | grep . | median)
  r=$(tr ' ' '\n' <<<"${rss[$order]}" | grep . | median)
  eval "w_$order=$w r_$order=$r"
  awk -v o="$order" -v n="$N" -v w="$w" -v r="$r" \
    'BEGIN { printf "| %s | %d | %.3f | %.1f |\n", o, n, w, r / 1024 }'
done
# shellcheck disable=SC2154
awk -v a="$w_space" -v b="$w_bfs" -v c="$r_space" -v d="$r_bfs" \
  'BEGIN { printf "space / bfs: time %.2fx, peak memory %.2fx\n", a / b, c / d }'
