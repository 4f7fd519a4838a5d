#!/usr/bin/env bash
# Before/after, side by side in one run: the L-system scaling driver and the
# growth driver of two builds, interleaved run by run so machine noise hits
# both alike. Medians of RUNS runs; peak RSS from GNU time.
#
#   benches/compare.sh BEFORE_DIR AFTER_DIR
#
# Each DIR holds `bench_lsys` and `bench_grow` (target/release/examples of
# the two builds). Results go into docs/performance.md by hand.
set -euo pipefail
B=$1 A=$2
RUNS=${RUNS:-5}
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
measure() { # label, then args after the binary name
    local label=$1 prog=$2; shift 2
    local bt=() at=() br=() ar=()
    for _ in $(seq "$RUNS"); do
        for side in B A; do
            local dir=$B; [ $side = A ] && dir=$A
            local o
            o=$(/usr/bin/time -f "RSS %M WALL %e" "$dir/$prog" "$@" 2>&1 >/dev/null)
            local t r
            t=$(sed -n 's/.*WALL \([0-9.]*\).*/\1/p' <<<"$o")
            r=$(sed -n 's/^RSS \([0-9]*\).*/\1/p' <<<"$o")
            if [ $side = B ]; then bt+=("$t"); br+=("$r"); else at+=("$t"); ar+=("$r"); fi
        done
    done
    local bm am bmr amr
    bm=$(printf '%s\n' "${bt[@]}" | median); am=$(printf '%s\n' "${at[@]}" | median)
    bmr=$(printf '%s\n' "${br[@]}" | median); amr=$(printf '%s\n' "${ar[@]}" | median)
    awk -v l="$label" -v b="$bm" -v a="$am" -v br="$bmr" -v ar="$amr" 'BEGIN {
        printf "| %s | %.3f | %.3f | %.2f | %.1f | %.1f |\n", l, b, a, a / b, br / 1024, ar / 1024 }'
}
echo "| work | before s | after s | after/before | before MB | after MB |"
echo "| --- | ---: | ---: | ---: | ---: | ---: |"
for d in 9 10 11 12; do
    measure "lsys bounds dfs, depth $d" bench_lsys bounds dfs "$d"
done
for d in 9 10; do
    measure "lsys bounds bfs, depth $d" bench_lsys bounds bfs "$d"
done
measure "lsys stats, depth 57" bench_lsys stats dfs 57
for s in bfs dfs; do
    # Width 0.0001: stems as drawn keep the clearance between their edges
    # since 0.2; so thin a stroke grows the same tree as the centre lines did.
    measure "grow $s, 10^5 stems" bench_grow "$s" rstar 100000 4000 0.0001
    measure "grow $s, 10^6 stems" bench_grow "$s" rstar 1000000 4000 0.0001
done
