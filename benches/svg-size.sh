#!/usr/bin/env bash
# SVG bounded by the picture (issue 24, item 3): whole-process `stlc render
# -f svg` of two builds side by side, in one run (per case, BEFORE's runs
# then AFTER's), at the default size. Medians of RUNS
# runs (default 5) of wall time and peak RSS (GNU time), the SVG's bytes
# and its path commands (`L` lines and `M` moves). BEFORE writes every
# segment (today's `--exact`); AFTER merges. "refused" where a build
# refuses the SVG at the default --max-svg-segments.
#
#   benches/svg-size.sh BEFORE_STLC AFTER_STLC
#   RUNS=3 benches/svg-size.sh /tmp/before/stlc target/release/stlc
set -euo pipefail
cd "$(dirname "$0")/.."
B=$1 A=$2
RUNS=${RUNS:-5}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }

one() { # svg command... -> "secs rss_kb" or "refused -"
    local o t0 t1
    t0=$(date +%s%N)
    o=$(/usr/bin/time -f "RSS %M" "$@" 2>&1 >/dev/null) || { echo "refused -"; return; }
    t1=$(date +%s%N)
    echo "$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", (b - a) / 1e9 }') $(awk '/^RSS/ {print $2}' <<<"$o")"
}

# Runs the command RUNS times; prints "median_s median_MB bytes lines moves".
measure() {
    local svg=$1
    shift
    local s="" m="" r t k
    for ((r = 0; r < RUNS; r++)); do
        read -r t k <<<"$(one "$@" -o "$svg")"
        [ "$t" = refused ] && { echo "refused - - - -"; return; }
        s+="$t " m+="$k "
    done
    local ms mm
    ms=$(tr ' ' '\n' <<<"$s" | grep -v '^$' | median)
    mm=$(tr ' ' '\n' <<<"$m" | grep -v '^$' | median)
    echo "$ms $(awk -v k="$mm" 'BEGIN { printf "%.0f", k / 1024 }') $(wc -c <"$svg") $(grep -o ' L' "$svg" | wc -l) $(($(grep -o ' M' "$svg" | wc -l) + $(grep -c 'd="M' "$svg")))"
}

CASES=(
    "examples/abop-1.24a.lsys"
    "examples/abop-1.24a.lsys --depth 8"
    "examples/abop-1.24a.lsys --depth 11"
    "examples/abop-1.24a.lsys --depth 57"
    "examples/abop-1.24d.lsys"
    "examples/hilbert.lsys"
    "examples/hilbert.lsys --depth 10"
    "examples/hilbert.lsys --depth 12"
    "examples/hilbert.lsys --depth 30"
    "examples/abop-1.27.lsys --depth 9"
    "examples/abop-1.27.lsys --depth 12"
    "examples/grove.od"
)

echo "| render -f svg | before s | MB | bytes | L | M | after s | MB | bytes | L | M |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
for c in "${CASES[@]}"; do
    # shellcheck disable=SC2086
    before=$(measure "$OUT/b.svg" $B render $c -q -f svg)
    # shellcheck disable=SC2086
    after=$(measure "$OUT/a.svg" $A render $c -q -f svg)
    echo "| \`$c\` | ${before// / | } | ${after// / | } |"
done
