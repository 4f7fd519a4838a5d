#!/usr/bin/env bash
# Growth in space against growth in the plane, side by side in one run
# (docs/3d.md, *Growth in volumes*; docs/performance.md): the benchmark tree
# of examples/bench_grow.rs (R1 = [-F][F][+F], L=1, B=0.1, A=30) grown to
# N stems (default 10^5) in a 4000 x 4000 rectangle (2D), in that
# rectangle extruded (3D, planar: the 2D decisions through the 3D grower
# and the prism's exact test) and in a 4000-unit cube with D=137.5 (3D,
# spreading in all three dimensions), bfs and dfs. Medians of RUNS runs
# (runs interleaved, so machine noise hits every row alike); peak RSS from
# GNU time -v. Builds the release example first.
#
#   benches/grow3d.sh [N]
set -euo pipefail
N=${1:-100000}
RUNS=${RUNS:-5}
cargo build --release --example bench_grow >/dev/null 2>&1
B=target/release/examples/bench_grow
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
rows=(
  "2D rectangle, bfs|bfs rstar $N 4000 0.1 plane"
  "3D extruded rectangle (planar), bfs|bfs rstar $N 4000 0.1 prism"
  "3D cube, D=137.5, bfs|bfs rstar $N 4000 0.1 cube"
  "2D rectangle, dfs|dfs rstar $N 4000 0.1 plane"
  "3D extruded rectangle (planar), dfs|dfs rstar $N 4000 0.1 prism"
  "3D cube, D=137.5, dfs|dfs rstar $N 4000 0.1 cube"
)
declare -A wall rss stems tries
for _ in $(seq "$RUNS"); do
  for i in "${!rows[@]}"; do
    IFS='|' read -r _ args <<<"${rows[$i]}"
    # shellcheck disable=SC2086
    o=$(/usr/bin/time -v "$B" $args 2>&1)
    wall[$i]+="$(sed -n 's/.*time=\([0-9.]*\)s.*/\1/p' <<<"$o") "
    rss[$i]+="$(sed -n 's/.*Maximum resident set size (kbytes): \([0-9]*\).*/\1/p' <<<"$o") "
    stems[$i]=$(sed -n 's/.*stems=\([0-9]*\).*/\1/p' <<<"$o")
    tries[$i]=$(sed -n 's/.*tries=\([0-9]*\).*/\1/p' <<<"$o")
  done
done
echo "| growth | stems | tries | median s (growth) | peak MB |"
echo "| --- | ---: | ---: | ---: | ---: |"
for i in "${!rows[@]}"; do
  IFS='|' read -r label _ <<<"${rows[$i]}"
  w=$(tr ' ' '\n' <<<"${wall[$i]}" | grep . | median)
  r=$(tr ' ' '\n' <<<"${rss[$i]}" | grep . | median)
  awk -v l="$label" -v n="${stems[$i]}" -v t="${tries[$i]}" -v w="$w" -v r="$r" \
    'BEGIN { printf "| %s | %d | %d | %.3f | %.1f |\n", l, n, t, w, r / 1024 }'
done
