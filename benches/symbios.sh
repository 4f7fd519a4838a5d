#!/usr/bin/env bash
# Parametric derivation, stlc against the `symbios` crate (issue 32;
# docs/performance.md, *Against symbios*), on Honda's tree (ABOP 2.6a)
# and Anabaena (ABOP 1.35), side by side: every run of every row for
# every engine interleaved, medians of RUNS runs.
#
# benches/symbios/ is a crate of its own (not a workspace member, so
# symbios never enters stlc's build) that derives the same systems with
# both engines in-process, the derivation alone timed (`modules s
# modules/s`, wall clock, which load inflates). Beside it the stlc
# binary's `stats` (derivation and the
# turtle's box) and `expand` (the word derived twice, counted then
# written, into a file). Every process runs under GNU time: CPU seconds
# (user + system) and peak resident memory.
#
#   benches/symbios.sh           # build both, check the words agree, measure
#   RUNS=5 HONDA=18 ANABAENA="400 600" benches/symbios.sh
#   NO_BUILD=1 benches/symbios.sh  # the binaries as they are
set -euo pipefail
cd "$(dirname "$0")/.."
RUNS=${RUNS:-5}
HONDA=${HONDA:-18}
ANABAENA=${ANABAENA:-400 600}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
if [ -z "${NO_BUILD:-}" ]; then # NO_BUILD=1: measure the binaries as built
  cargo build --release --locked --quiet --bin stlc
  cargo build --release --locked --quiet --manifest-path benches/symbios/Cargo.toml \
    --target-dir target/symbios-bench
fi
B=target/symbios-bench/release/symbios-bench
S=target/release/stlc

# Fair only if both derive the same word: every generation's word, module
# for module and parameter for parameter (shortest round-trip numbers),
# to a depth where that is quick.
"$B" words honda 12
"$B" words anabaena 400

median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
rows=(
  "Honda 2.6a depth $HONDA: symbios, derive|$B symbios honda $HONDA"
  "Honda 2.6a depth $HONDA: stlc, derive|$B stlc honda $HONDA"
  "Honda 2.6a depth $HONDA: stlc stats|$S stats examples/abop-2.6a.lsys --depth $HONDA"
  "Honda 2.6a depth $HONDA: stlc expand|$S expand examples/abop-2.6a.lsys --depth $HONDA -o $T/h.txt"
)
for a in $ANABAENA; do
  rows+=(
    "Anabaena 1.35 depth $a: symbios, derive|$B symbios anabaena $a"
    "Anabaena 1.35 depth $a: stlc, derive|$B stlc anabaena $a"
    "Anabaena 1.35 depth $a: stlc stats|$S stats examples/abop-1.35.lsys --depth $a"
    "Anabaena 1.35 depth $a: stlc expand|$S expand examples/abop-1.35.lsys --depth $a -o $T/a.txt"
  )
done
declare -A cpu rss wall rate mods
for _ in $(seq "$RUNS"); do
  for i in "${!rows[@]}"; do
    IFS='|' read -r _ cmd <<<"${rows[$i]}"
    # shellcheck disable=SC2086
    /usr/bin/time -o "$T/time" -f "%U %S %M" $cmd >"$T/out"
    cpu[$i]+="$(awk '{print $1 + $2}' "$T/time") "
    rss[$i]+="$(awk '{print $3 / 1024}' "$T/time") "
    if [[ $cmd == "$B "* ]]; then
      read -r n s r <"$T/out"
      mods[$i]=$n
      wall[$i]+="$s "
      rate[$i]+="$r "
    fi
  done
done
echo "| work | modules | derivation s | modules/s | CPU s | modules/CPU s | peak RSS MB |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: |"
for i in "${!rows[@]}"; do
  IFS='|' read -r label _ <<<"${rows[$i]}"
  m() { tr ' ' '\n' <<<"$1" | grep . | median; }
  if [ -n "${wall[$i]:-}" ]; then
    c=$(m "${cpu[$i]}")
    printf '| %s | %s | %.4f | %.3g | %s | %.3g | %.1f |\n' "$label" "${mods[$i]}" \
      "$(m "${wall[$i]}")" "$(m "${rate[$i]}")" "$c" "$(awk -v n="${mods[$i]}" -v c="$c" 'BEGIN {print (c > 0 ? n / c : 0)}')" "$(m "${rss[$i]}")"
  else
    printf '| %s | | | | %s | | %.1f |\n' "$label" "$(m "${cpu[$i]}")" "$(m "${rss[$i]}")"
  fi
done
