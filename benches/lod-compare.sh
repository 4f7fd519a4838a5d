#!/usr/bin/env bash
# Level of detail and memoized geometry (issue 12): whole-process
# `stlc render` and `stlc stats --json` of two builds side by side, in one
# run, interleaved run by run (BEFORE, AFTER, BEFORE, AFTER, ...) so that
# machine noise (other builds on a shared 2-core host) hits both alike.
# Medians of RUNS runs; peak RSS from GNU time (/usr/bin/time -f %M).
#
#   benches/lod-compare.sh BEFORE_STLC AFTER_STLC
#   RUNS=5 DEPTHS="6 8 10" benches/lod-compare.sh /tmp/before/stlc target/release/stlc
#
# System: LSYS, default examples/abop-1.24a.lsys (F -> F[+F]F[-F]F, 25.7
# degrees); also run with LSYS=examples/abop-1.27.lsys (stochastic) and
# LSYS=examples/hilbert.lsys (a space-filling curve) for issue 24.
# "before" is run only where it finishes in reasonable time (word up to
# depth MAX_BEFORE, default 11, and not at all where it refuses: it has no
# memo, so depth 57 is over --max-symbols). AFTER also runs with --exact at
# the depths where BEFORE runs, to show it is today's renderer. Output: a
# markdown table for docs/performance.md.
set -euo pipefail
cd "$(dirname "$0")/.."
B=$1 A=$2
RUNS=${RUNS:-3}
DEPTHS=${DEPTHS:-"6 7 8 9 10 11 12 13 15 20 30 40 57"}
SIZES=${SIZES:-"800 2048x2048"}
MAX_BEFORE=${MAX_BEFORE:-11}
LSYS=${LSYS:-examples/abop-1.24a.lsys}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }

one() { # command... -> "secs rss_kb" or "fail -"
    local o t0 t1
    t0=$(date +%s%N)
    o=$(/usr/bin/time -f "RSS %M" "$@" 2>&1 >/dev/null) || { echo "fail -"; return; }
    t1=$(date +%s%N)
    echo "$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", (b - a) / 1e9 }') $(awk '/^RSS/ {print $2}' <<<"$o")"
}

# Runs up to three commands interleaved RUNS times; prints their medians
# as "s MB" pairs ("- -" for a command given as "-").
interleave() {
    local -a cmds=("$@") secs rss
    local i r
    for ((i = 0; i < ${#cmds[@]}; i++)); do secs[i]=""; rss[i]=""; done
    for ((r = 0; r < RUNS; r++)); do
        for ((i = 0; i < ${#cmds[@]}; i++)); do
            [ "${cmds[i]}" = "-" ] && continue
            read -r s m <<<"$(eval "one ${cmds[i]}")"
            secs[i]+="$s "
            rss[i]+="$m "
        done
    done
    for ((i = 0; i < ${#cmds[@]}; i++)); do
        if [ "${cmds[i]}" = "-" ]; then
            printf -- "- - "
        else
            local ms mr
            ms=$(tr ' ' '\n' <<<"${secs[i]}" | grep -v '^$' | median)
            mr=$(tr ' ' '\n' <<<"${rss[i]}" | grep -v '^$' | median)
            printf "%s %s " "$ms" "$(awk -v k="$mr" 'BEGIN { if (k == "-" || k == "") print "-"; else printf "%.1f", k / 1024 }')"
        fi
    done
    echo
}

echo "| size | depth | before s | before MB | after --exact s | after --exact MB | after (LOD) s | after MB | before/after |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
for size in $SIZES; do
    flag=()
    [ "$size" != 800 ] && flag=(--size "$size")
    for d in $DEPTHS; do
        if [ "$d" -le "$MAX_BEFORE" ]; then
            before="$B render $LSYS --depth $d ${flag[*]} -o $OUT/b.png"
            exact="$A render $LSYS --depth $d ${flag[*]} --exact -o $OUT/x.png"
        else
            before=- exact=-
        fi
        after="$A render $LSYS --depth $d ${flag[*]} -o $OUT/a.png"
        read -r bs bm xs xm as am <<<"$(interleave "$before" "$exact" "$after")"
        ratio=$(awk -v b="$bs" -v a="$as" 'BEGIN { if (b == "-" || b == "fail" || a == 0) print "-"; else printf "%.1f", b / a }')
        echo "| $size | $d | $bs | $bm | $xs | $xm | $as | $am | $ratio |"
    done
done
echo
echo "| stats --json | before s | before MB | after s | after MB | after has bbox |"
echo "| ---: | ---: | ---: | ---: | ---: | --- |"
for d in 11 13 30 57; do
    read -r bs bm as am <<<"$(interleave "$B stats $LSYS --depth $d --json" "$A stats $LSYS --depth $d --json")"
    has=$("$A" stats "$LSYS" --depth "$d" --json | grep -q '"bbox": \[' && echo yes || echo no)
    echo "| depth $d | $bs | $bm | $as | $am | $has |"
done
