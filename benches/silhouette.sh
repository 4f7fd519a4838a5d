#!/usr/bin/env bash
# What sampled stand-ins cost (issue 24 item 4; docs/rendering.md,
# *Silhouette*; docs/performance.md): the renders of the acceptance list,
# with two builds side by side, runs interleaved so machine noise hits
# both alike. Medians of RUNS runs of the whole process (wall seconds) and
# the largest peak RSS (GNU time -v).
#
#   BEFORE=/path/to/old/stlc AFTER=target/release/stlc benches/silhouette.sh
#
# (Without AFTER, builds this checkout's release stlc; BEFORE is required:
# build another commit with `git worktree add`.)
set -euo pipefail
cd "$(dirname "$0")/.."
RUNS=${RUNS:-5}
: "${BEFORE:?set BEFORE to another build of stlc}"
if [ -z "${AFTER:-}" ]; then
    cargo build --release --bin stlc >&2
    AFTER=${CARGO_TARGET_DIR:-target}/release/stlc
fi
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
rows=(
  "abop-1.24a --depth 11"
  "abop-1.24a --depth 57 --size 2048x2048"
  "abop-1.27 --depth 20"
  "abop-1.27 --depth 57"
  "stl-003-fig4 --depth 11"
  "hilbert --depth 13 --size 2048x2048"
  "hilbert --depth 30 --size 2048x2048"
  "hilbert --depth 11 --size 512x512"
  "abop-1.24b --depth 30"
)
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
largest() { sort -g | tail -1; }
declare -A wall rss
for _ in $(seq "$RUNS"); do
  for i in "${!rows[@]}"; do
    read -r name args <<<"${rows[$i]}"
    for b in before after; do
      bin=$BEFORE; [ $b = after ] && bin=$AFTER
      # shellcheck disable=SC2086
      o=$(/usr/bin/time -f "%e %M" "$bin" render "examples/$name.lsys" $args -o "$OUT/p.png" 2>&1 | tail -1)
      wall[$i$b]+="${o% *}"$'\n'
      rss[$i$b]+="${o#* }"$'\n'
    done
  done
done
echo "| render | before s | after s | ratio | before MB | after MB |"
echo "| --- | ---: | ---: | ---: | ---: | ---: |"
for i in "${!rows[@]}"; do
  wb=$(median <<<"${wall[${i}before]}"); wa=$(median <<<"${wall[${i}after]}")
  rb=$(largest <<<"${rss[${i}before]}"); ra=$(largest <<<"${rss[${i}after]}")
  awk -v r="${rows[$i]}" -v wb="$wb" -v wa="$wa" -v rb="$rb" -v ra="$ra" \
    'BEGIN { printf "| %s | %.2f | %.2f | %.2fx | %.0f | %.0f |\n", r, wb, wa, (wb > 0 ? wa / wb : 0), rb / 1024, ra / 1024 }'
done
