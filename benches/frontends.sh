#!/usr/bin/env bash
# The front ends before/after, side by side in one run: CLI commands of two
# `stlc` binaries interleaved run by run, and `stlc serve`'s POST
# /api/render answered by each (the server's own time, over loopback with
# curl). Medians of RUNS runs; peak RSS of the CLI runs from GNU time.
#
#   benches/frontends.sh BEFORE_STLC AFTER_STLC
#
# Run from the repository root. Results go into docs/performance.md by hand.
set -euo pipefail
B=$(realpath "$1") A=$(realpath "$2")
RUNS=${RUNS:-7}
EX=examples
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

cli() { # label, then the arguments after the binary
    local label=$1; shift
    local bt=() at=() br=() ar=()
    for _ in $(seq "$RUNS"); do
        for side in B A; do
            local bin=$B; [ $side = A ] && bin=$A
            local o t r
            o=$(/usr/bin/time -f "RSS %M WALL %e" "$bin" "$@" 2>&1 >/dev/null | tail -1)
            t=$(sed -n 's/.*WALL \([0-9.]*\).*/\1/p' <<<"$o")
            r=$(sed -n 's/^RSS \([0-9]*\).*/\1/p' <<<"$o")
            if [ $side = B ]; then bt+=("$t"); br+=("$r"); else at+=("$t"); ar+=("$r"); fi
        done
    done
    local bm am bmr amr
    bm=$(printf '%s\n' "${bt[@]}" | median); am=$(printf '%s\n' "${at[@]}" | median)
    bmr=$(printf '%s\n' "${br[@]}" | median); amr=$(printf '%s\n' "${ar[@]}" | median)
    awk -v l="$label" -v b="$bm" -v a="$am" -v br="$bmr" -v ar="$amr" 'BEGIN {
        printf "| %s | %.3f | %.3f | %.2f | %.1f | %.1f |\n", l, b, a, (b > 0 ? a / b : 1), br / 1024, ar / 1024 }'
}

echo "| work | before s | after s | after/before | before MB | after MB |"
echo "| --- | ---: | ---: | ---: | ---: | ---: |"
cli "render abop-1.24a depth 10 --exact" render $EX/abop-1.24a.lsys --depth 10 --exact -o "$out/a.png"
cli "render abop-1.24a depth 20, 3000x3000" render $EX/abop-1.24a.lsys --depth 20 --size 3000x3000 -o "$out/b.png"
cli "render grove.od --show-layout" render $EX/grove.od --show-layout -o "$out/c.png"
cli "render holes.od -f svg" render $EX/holes.od -o "$out/d.svg"
cli "compile holes.od --growth dfs" compile $EX/holes.od --growth dfs -o "$out/e.bed"
cli "check 2dtree.od" check $EX/2dtree.od
cli "expand hilbert.lsys depth 9" expand $EX/hilbert.lsys --depth 9 -o "$out/f.txt"

# serve: the same request to each server, interleaved; curl's total time.
start() { # binary -> "port token"
    local port=$((20000 + RANDOM % 20000))
    "$1" serve --port "$port" >"$out/serve.$port" 2>&1 &
    echo $! >"$out/pid.$port"
    sleep 1
    local url token
    url=$(head -1 "$out/serve.$port")
    token=$(sed -n 's/.*token=\([0-9a-f]*\).*/\1/p' <<<"$url")
    echo "$port ${token:-none}"
}
read -r bp bt < <(start "$B")
read -r ap at < <(start "$A")
post() { # port token file -> seconds
    curl -s -o /dev/null -w '%{time_total}\n' -H "Authorization: Bearer $2" \
        -H "Content-Type: application/json" --data-binary @"$3" "http://127.0.0.1:$1/api/render"
}
echo
echo "| POST /api/render | before ms | after ms | after/before |"
echo "| --- | ---: | ---: | ---: |"
for f in 2dtree.od holes.od grove.od; do
    jq -n --rawfile s "$EX/$f" '{source: $s, kind: "od", strategy: "bfs"}' >"$out/req.json"
    post "$bp" "$bt" "$out/req.json" >/dev/null; post "$ap" "$at" "$out/req.json" >/dev/null
    bts=() ats=()
    for _ in $(seq $((RUNS * 3))); do
        bts+=("$(post "$bp" "$bt" "$out/req.json")")
        ats+=("$(post "$ap" "$at" "$out/req.json")")
    done
    bm=$(printf '%s\n' "${bts[@]}" | median); am=$(printf '%s\n' "${ats[@]}" | median)
    awk -v l="$f" -v b="$bm" -v a="$am" 'BEGIN { printf "| %s | %.1f | %.1f | %.2f |\n", l, b * 1000, a * 1000, a / b }'
done
kill "$(cat "$out/pid.$bp")" "$(cat "$out/pid.$ap")" 2>/dev/null || true
