#!/usr/bin/env bash
# Parametric L-systems (docs/lsys.md, *Measured*), and the classic path
# they must not slow: CPU seconds (user + system, from GNU time), medians
# of RUNS runs, binaries interleaved so machine noise hits each alike.
# Needs a release build: `cargo build --release`.
#
#   benches/param.sh [STLC...]   # several binaries: side by side
set -euo pipefail
RUNS=${RUNS:-5}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
rows=(
  "classic: ABOP 1.24a depth 11, PNG --exact|render examples/abop-1.24a.lsys --depth 11 --exact --threads 1 -o $T/a.png"
  "classic: Hilbert depth 12, PNG --exact|render examples/hilbert.lsys --depth 12 --exact --threads 1 -o $T/b.png"
  "classic: ABOP 1.24a depth 11, PNG|render examples/abop-1.24a.lsys --depth 11 -o $T/c.png"
  "classic: ABOP 1.24a depth 9, expand|expand examples/abop-1.24a.lsys --depth 9 -o $T/d.txt"
  "parametric: ABOP 2.6a depth 18 (262143 segments), 2048 px view|render examples/abop-2.6a.lsys --depth 18 --view 0,0 --size 2048x2048 -o $T/e.png"
  "parametric: ABOP 2.6a depth 18 (1835002 modules), expand|expand examples/abop-2.6a.lsys --depth 18 -o $T/f.txt"
  "parametric: ABOP 2.8b depth 8, 2048 px view|render examples/abop-2.8b.lsys --size 2048x2048 -o $T/g.png"
  "context: ABOP 1.35 Anabaena depth 400, stats|stats examples/abop-1.35.lsys --depth 400"
  "context: ABOP 1.31a depth 30, expand|expand examples/abop-1.31a.lsys -o $T/h.txt"
  "parametric: ABOP 2.6a depth 18, 2048 px default view|render examples/abop-2.6a.lsys --depth 18 --size 2048x2048 -o $T/i.png"
  "context: ABOP 1.35 Anabaena depth 400 (see docs), expand|expand examples/abop-1.35.lsys --depth 400 -o $T/j.txt"
  "level of detail, classic: ABOP 1.24a depth 14, 2048 px|render examples/abop-1.24a.lsys --depth 14 --size 2048x2048 -o $T/k.png"
  "level of detail, stochastic: ABOP 1.27 depth 14, 2048 px|render examples/abop-1.27.lsys --depth 14 --size 2048x2048 -o $T/l.png"
  "level of detail, 3D: plant3d depth 12, 2048 px view|render examples/plant3d-bare.lsys --depth 12 --size 2048x2048 -o $T/m.png"
  "level of detail, parametric: benches/param-fan.lsys depth 20, 2048 px|render benches/param-fan.lsys --depth 20 --size 2048x2048 -o $T/n.png"
  "level of detail, parametric: benches/param-fan.lsys depth 40, 2048 px, --max-symbols 3e8|render benches/param-fan.lsys --depth 40 --size 2048x2048 --max-symbols 300000000 -o $T/o.png"
)
BINS=("$@")
[ ${#BINS[@]} -eq 0 ] && BINS=(target/release/stlc)
declare -A cpu fail
for _ in $(seq "$RUNS"); do
  for i in "${!rows[@]}"; do
    for b in "${!BINS[@]}"; do
      IFS='|' read -r _ args <<<"${rows[$i]}"
      # shellcheck disable=SC2086
      if /usr/bin/time -o "$T/time" -f "%U %S" "${BINS[$b]}" $args >/dev/null 2>&1; then
        cpu[$i.$b]+="$(awk '{print $1 + $2}' "$T/time") "
      else
        fail[$i.$b]=1
      fi
    done
  done
done
head="| work |"
sep="| --- |"
for b in "${!BINS[@]}"; do
  head+=" ${BINS[$b]} CPU s |"
  sep+=" ---: |"
done
echo "$head"
echo "$sep"
for i in "${!rows[@]}"; do
  IFS='|' read -r label _ <<<"${rows[$i]}"
  line="| $label |"
  for b in "${!BINS[@]}"; do
    if [ -n "${fail[$i.$b]:-}" ]; then
      line+=" refused |"
      continue
    fi
    line+=" $(tr ' ' '\n' <<<"${cpu[$i.$b]}" | grep . | median) |"
  done
  echo "$line"
done
