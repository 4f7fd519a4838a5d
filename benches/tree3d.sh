#!/usr/bin/env bash
# 3D BEDs against 2D BEDs, side by side in one run (docs/3d.md, *A 3D OD
# or BED*): one BED of 2^17 - 1 stems (`F [I 16 R1]`, `R1: [+F][-F]`) as
# a 2D BED and as a 3D BED (root `(0, 0, 0)`, `D=137.5`): its PNG (2D
# picture; 3D view 30,20) and the 3D one's .glb; and the expansion (the
# interpreter alone) of the same with `[I 22 R1]`, 2^23 - 1 stems. With a second binary BASE (a build from before the 3D BED
# interpreter), its 2D rows run too, interleaved: the 2D interpreter's
# generic stream must cost what the plain one did. Medians of RUNS runs;
# peak RSS from GNU time. Needs a release build: `cargo build --release`.
#
#   benches/tree3d.sh [STLC [BASE]]
set -euo pipefail
B=${1:-target/release/stlc}
BASE=${2:-}
RUNS=${RUNS:-5}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
printf 'T (0, 0) L=10(0.4) B=1(0) A=25 RULE R1: [+F][-F] SEED F [I 16 R1] ENDSEED\n' >"$T/flat.bed"
printf 'T (0, 0, 0) L=10(0.4) B=1(0) A=25 D=137.5 RULE R1: [+F][-F] SEED F [I 16 R1] ENDSEED\n' >"$T/deep.bed"
# The expansions (the interpreter alone, no picture) of 2^23 - 1 stems.
sed 's/I 16/I 22/' "$T/flat.bed" >"$T/flat22.bed"
sed 's/I 16/I 22/' "$T/deep.bed" >"$T/deep22.bed"
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
rows=(
  "2D BED expand, 8388607 stems|$B|expand $T/flat22.bed -o $T/a.txt"
  "2D BED PNG, 131071 stems|$B|render $T/flat.bed -o $T/b.png"
  "3D BED expand, 8388607 stems|$B|expand $T/deep22.bed -o $T/c.txt"
  "3D BED view 30,20 PNG|$B|render $T/deep.bed -o $T/d.png"
  "3D BED .glb|$B|render $T/deep.bed -o $T/e.glb"
)
if [ -n "$BASE" ]; then
  rows+=(
    "2D BED expand (BASE)|$BASE|expand $T/flat22.bed -o $T/f.txt"
    "2D BED PNG (BASE)|$BASE|render $T/flat.bed -o $T/g.png"
  )
fi
declare -A wall rss
for _ in $(seq "$RUNS"); do
  for i in "${!rows[@]}"; do
    IFS='|' read -r _ bin args <<<"${rows[$i]}"
    # shellcheck disable=SC2086
    o=$(/usr/bin/time -f "RSS %M WALL %e" "$bin" $args 2>&1 >/dev/null | tail -1)
    wall[$i]+="$(sed -n 's/.*WALL \([0-9.]*\).*/\1/p' <<<"$o") "
    rss[$i]+="$(sed -n 's/^RSS \([0-9]*\).*/\1/p' <<<"$o") "
  done
done
echo "| work | median s | peak MB |"
echo "| --- | ---: | ---: |"
for i in "${!rows[@]}"; do
  IFS='|' read -r label _ _ <<<"${rows[$i]}"
  w=$(tr ' ' '\n' <<<"${wall[$i]}" | grep . | median)
  r=$(tr ' ' '\n' <<<"${rss[$i]}" | grep . | median)
  awk -v l="$label" -v w="$w" -v r="$r" 'BEGIN { printf "| %s | %.3f | %.1f |\n", l, w, r / 1024 }'
done
