#!/usr/bin/env bash
# Classic L-system scaling: dfs against bfs for F -> F[+F]F[-F]F (angle 25.7)
# at depths 8..13, wall time (median of 3 runs), peak RSS and symbols/s of
# the bounding pass (what `stats` and the renderer's first pass do), plus
# `stats` at depth 57. Results go into docs/performance.md by hand.
#
#   benches/lsys-scale.sh            # depths 8..13
#   DEPTHS="8 9" benches/lsys-scale.sh
set -euo pipefail
cd "$(dirname "$0")/.."
if ! [ -x /usr/bin/time ]; then
    echo "installing GNU time (apt-get install -y time)" >&2
    apt-get install -y time >/dev/null
fi
cargo build --release --example bench_lsys >&2
BIN=target/release/examples/bench_lsys
DEPTHS=${DEPTHS:-"8 9 10 11 12 13"}
RUNS=${RUNS:-3}

median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }

run() { # mode strategy depth -> "secs rss_kb msym_s" (medians)
    local secs=() rss=() rate=()
    for _ in $(seq "$RUNS"); do
        local out
        out=$(/usr/bin/time -f "RSS %M" "$BIN" "$@" 2>&1) || { echo "fail - -"; return; }
        secs+=("$(sed -n 's/.*secs=\([0-9.]*\).*/\1/p' <<<"$out")")
        rate+=("$(sed -n 's/.*Msym\/s=\([0-9.]*\).*/\1/p' <<<"$out")")
        rss+=("$(sed -n 's/^RSS \([0-9]*\)/\1/p' <<<"$out")")
    done
    echo "$(printf '%s\n' "${secs[@]}" | median) $(printf '%s\n' "${rss[@]}" | median) $(printf '%s\n' "${rate[@]}" | median)"
}

echo "| depth | symbols | dfs s | dfs peak RSS MB | dfs M sym/s | bfs s | bfs peak RSS MB | bfs M sym/s | bfs/dfs time |"
echo "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
for d in $DEPTHS; do
    sym=$(( (5 ** (d + 1) - 3) / 2 ))
    read -r ds dr dm <<<"$(run bounds dfs "$d")"
    # bfs holds the word: one byte per symbol, two levels at once.
    if [ "$sym" -le 1000000000 ]; then
        read -r bs br bm <<<"$(run bounds bfs "$d")"
    else
        bs=- br=- bm=-
    fi
    ratio=$(awk -v a="$bs" -v b="$ds" 'BEGIN { if (a == "-" || a == "fail") print "-"; else printf "%.1f", a / b }')
    mb() { awk -v k="$1" 'BEGIN { if (k == "-" || k == "") print "-"; else printf "%.1f", k / 1024 }'; }
    echo "| $d | $sym | $ds | $(mb "$dr") | $dm | $bs | $(mb "$br") | $bm | $ratio |"
done
echo
echo "stats at depth 57:"
/usr/bin/time -f "wall %e s, peak RSS %M KB" "$BIN" stats dfs 57
