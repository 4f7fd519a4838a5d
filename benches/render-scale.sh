#!/usr/bin/env bash
# Classic L-system rendering at scale: `stlc render` (dfs and bfs) and
# `stlc stats` for F -> F[+F]F[-F]F (angle 25.7, examples/abop-1.24a.lsys)
# at depths 8..13, whole-process wall time in ms (median of RUNS runs; depths 12
# and up run once), peak RSS and M symbols/s. Output: the default 800 px
# PNG. Results go into docs/performance.md (### Rendering) by hand.
#
#   benches/render-scale.sh                 # depths 8..13
#   DEPTHS="8 9" RUNS=5 benches/render-scale.sh
#   STLC=/tmp/stlc-old EXACT= benches/render-scale.sh   # another build (one without --exact)
#
# dfs renders with --exact (every segment, the renderer this table has
# always measured); the level of detail, on by default since issue 12, is
# measured by benches/lod-compare.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! [ -x /usr/bin/time ]; then
    echo "installing GNU time (apt-get install -y time)" >&2
    apt-get install -y time >/dev/null
fi
if [ -z "${STLC:-}" ]; then
    cargo build --release --bin stlc >&2
    STLC=target/release/stlc
fi
DEPTHS=${DEPTHS:-"8 9 10 11 12 13"}
EXACT=${EXACT---exact}
RUNS=${RUNS:-3}
LSYS=examples/abop-1.24a.lsys
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }

run() { # runs command... -> "secs rss_kb" (medians), or "fail -"
    local n=$RUNS secs=() rss=()
    [ "$depth" -ge 12 ] && n=1
    for _ in $(seq "$n"); do
        local out
        local t0 t1
        t0=$(date +%s%N)
        out=$(/usr/bin/time -f "RSS %M" "$@" 2>&1 >/dev/null) || { echo "fail -"; return; }
        t1=$(date +%s%N)
        secs+=("$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", (b - a) / 1e9 }')")
        rss+=("$(awk '/^RSS/ {print $2}' <<<"$out")")
    done
    echo "$(printf '%s\n' "${secs[@]}" | median) $(printf '%s\n' "${rss[@]}" | median)"
}

mb() { awk -v k="$1" 'BEGIN { if (k == "-") print "-"; else printf "%.1f", k / 1024 }'; }
rate() { awk -v n="$1" -v s="$2" 'BEGIN { if (s == "-" || s == "fail" || s == 0) print "-"; else printf "%.1f", n / s / 1e6 }'; }

echo "| depth | symbols | segments | render dfs s | dfs MB | dfs M sym/s | render bfs s | bfs MB | bfs M sym/s | stats s | stats MB | stats M sym/s |"
echo "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
for depth in $DEPTHS; do
    sym=$(( (5 ** (depth + 1) - 3) / 2 ))
    seg=$(( 5 ** depth ))
    read -r ds dr <<<"$(run "$STLC" render "$LSYS" --depth "$depth" --strategy dfs $EXACT -o "$OUT/dfs.png")"
    # bfs holds the word (one byte per symbol, two levels at once): raise
    # --max-word for depth 12 (610 M symbols, about 0.75 GB); depth 13
    # would need about 4 GB and is not run.
    if [ "$depth" -le 12 ]; then
        read -r bs br <<<"$(run "$STLC" render "$LSYS" --depth "$depth" --strategy bfs \
            --max-word 1000000000 -o "$OUT/bfs.png")"
    else
        bs=- br=-
    fi
    read -r ss sr <<<"$(run "$STLC" stats "$LSYS" --depth "$depth")"
    echo "| $depth | $sym | $seg | $ds | $(mb "$dr") | $(rate "$sym" "$ds") | $bs | $(mb "$br") | $(rate "$sym" "$bs") | $ss | $(mb "$sr") | $(rate "$sym" "$ss") |"
done
