#!/usr/bin/env bash
# Both cores for --exact (issue 24, item 6): whole-process `stlc render`
# with --threads 1 and --threads 2 side by side, in one run, interleaved
# run by run (1, 2, 1, 2, ...) so that machine noise hits both alike.
# Medians of RUNS runs (default 5); peak RSS from GNU time. Each case
# also checks that both thread counts wrote the same bytes.
#
#   benches/threads.sh [STLC]        # default target/release/stlc
#   RUNS=3 benches/threads.sh
#
# Output: a markdown table for docs/performance.md, and the machine's
# load average before and after (the ratio means something only on an
# otherwise idle machine).
set -euo pipefail
cd "$(dirname "$0")/.."
S=${1:-target/release/stlc}
RUNS=${RUNS:-5}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }

one() { # output command... -> "secs rss_kb"
    local o t0 t1
    t0=$(date +%s%N)
    o=$(/usr/bin/time -f "RSS %M" "$@" 2>&1 >/dev/null) || { echo "fail -"; return; }
    t1=$(date +%s%N)
    echo "$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", (b - a) / 1e9 }') $(awk '/^RSS/ {print $2}' <<<"$o")"
}

CASES=(
    "examples/abop-1.24a.lsys --exact --depth 11 --size 2048x2048"
    "examples/abop-1.24a.lsys --exact --depth 11"
    "examples/hilbert.lsys --exact --depth 12 --size 2048x2048"
    "examples/abop-1.27.lsys --exact --depth 12 --size 2048x2048"
    "examples/abop-1.24a.lsys --depth 57 --size 2048x2048"
)

echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| render | threads 1 s | MB | threads 2 s | MB | 1 / 2 | same bytes |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | --- |"
for c in "${CASES[@]}"; do
    s1="" s2="" m1="" m2=""
    for ((r = 0; r < RUNS; r++)); do
        # shellcheck disable=SC2086
        read -r s m <<<"$(one $S render $c -q --threads 1 -o "$OUT/1.png")"
        s1+="$s " m1+="$m "
        # shellcheck disable=SC2086
        read -r s m <<<"$(one $S render $c -q --threads 2 -o "$OUT/2.png")"
        s2+="$s " m2+="$m "
    done
    a=$(tr ' ' '\n' <<<"$s1" | grep -v '^$' | median)
    b=$(tr ' ' '\n' <<<"$s2" | grep -v '^$' | median)
    ma=$(tr ' ' '\n' <<<"$m1" | grep -v '^$' | median)
    mb=$(tr ' ' '\n' <<<"$m2" | grep -v '^$' | median)
    same=$(cmp -s "$OUT/1.png" "$OUT/2.png" && echo yes || echo NO)
    printf "| \`%s\` | %s | %.0f | %s | %.0f | %.2f | %s |\n" "$c" "$a" "$((ma / 1024))" "$b" "$((mb / 1024))" \
        "$(awk -v a="$a" -v b="$b" 'BEGIN { print a / b }')" "$same"
done
echo
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
