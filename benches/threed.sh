#!/usr/bin/env bash
# 3D against 2D, side by side in one run (docs/3d.md, *Cost*): the same
# planar system drawn as a 2D picture (`--exact`, every segment, as a 3D
# view draws) and as a 3D view (`dimensions 3`, from the front and from
# 30,20); and mesh exports of about 10^5 stems. Medians of RUNS runs (runs
# interleaved, so machine noise hits every row alike); peak RSS from GNU
# time. Needs a release build: `cargo build --release`.
#
#   benches/threed.sh [STLC...]   # several binaries: side by side, interleaved
set -euo pipefail
B=${1:-target/release/stlc}
RUNS=${RUNS:-5}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
# F -> F[+F]F[-F]F at 25.7 degrees, depth 7: 5^7 = 78125 segments.
printf 'generations 7\nangle 25.7\naxiom F\nrule F F[+F]F[-F]F\n' >"$T/flat.lsys"
printf 'dimensions 3\n' | cat - "$T/flat.lsys" >"$T/deep.lsys"
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
rows=(
  "2D picture --exact, 78125 stems|render $T/flat.lsys --exact -o $T/a.png"
  "3D view 0,0, 78125 stems|render $T/deep.lsys --view 0,0 -o $T/b.png"
  "3D view 30,20, 78125 stems|render $T/deep.lsys -o $T/c.png"
  "3D bush (plant3d) depth 10, view|render examples/plant3d-bare.lsys --depth 10 -o $T/d.png"
  "3D bush depth 10 to .glb|render examples/plant3d-bare.lsys --depth 10 -o $T/e.glb"
  "3D bush depth 10 to .obj|render examples/plant3d-bare.lsys --depth 10 -o $T/f.obj"
  "2D picture as a mesh .glb, 78125 stems|render $T/flat.lsys -o $T/g.glb"
  "3D bush depth 10, view --exact|render examples/plant3d-bare.lsys --depth 10 --exact -o $T/h.png"
  "3D bush depth 13 stats (traversal, 29 M symbols)|stats examples/plant3d-bare.lsys --depth 13 --json"
  "3D bush depth 20, view (level of detail)|render examples/plant3d-bare.lsys --depth 20 -o $T/i.png"
  "3D bush depth 20, SVG view|render examples/plant3d-bare.lsys --depth 20 -o $T/j.svg"
  "3D Hilbert depth 7, view --exact (2 M stems)|render examples/hilbert3d.lsys --depth 7 --exact -o $T/k.png"
  "3D Hilbert depth 20, view (level of detail)|render examples/hilbert3d.lsys --depth 20 -o $T/l.png"
  "3D Hilbert depth 20 stats (exact box)|stats examples/hilbert3d.lsys --depth 20 --json"
)
# Every binary runs every row, interleaved; a refused command (an old
# binary over a limit) is listed as such.
BINS=("$@")
[ ${#BINS[@]} -eq 0 ] && BINS=("$B")
declare -A wall rss fail
for _ in $(seq "$RUNS"); do
  for i in "${!rows[@]}"; do
    for b in "${!BINS[@]}"; do
      IFS='|' read -r _ args <<<"${rows[$i]}"
      # shellcheck disable=SC2086
      if o=$(/usr/bin/time -f "RSS %M WALL %e" "${BINS[$b]}" $args 2>&1 >/dev/null | tail -2) &&
        grep -q '^RSS' <<<"$o" && ! grep -q 'exited with non-zero' <<<"$o"; then
        wall[$i.$b]+="$(sed -n 's/.*WALL \([0-9.]*\).*/\1/p' <<<"$o") "
        rss[$i.$b]+="$(sed -n 's/^RSS \([0-9]*\).*/\1/p' <<<"$o") "
      else
        fail[$i.$b]=1
      fi
    done
  done
done
head="| work |"
sep="| --- |"
for b in "${!BINS[@]}"; do
  head+=" ${BINS[$b]} s | peak MB |"
  sep+=" ---: | ---: |"
done
echo "$head"
echo "$sep"
for i in "${!rows[@]}"; do
  IFS='|' read -r label _ <<<"${rows[$i]}"
  line="| $label |"
  for b in "${!BINS[@]}"; do
    if [ -n "${fail[$i.$b]:-}" ]; then
      line+=" refused | |"
      continue
    fi
    w=$(tr ' ' '\n' <<<"${wall[$i.$b]}" | grep . | median)
    r=$(tr ' ' '\n' <<<"${rss[$i.$b]}" | grep . | median)
    line+=$(awk -v w="$w" -v r="$r" 'BEGIN { printf " %.3f | %.1f |", w, r / 1024 }')
  done
  echo "$line"
done
