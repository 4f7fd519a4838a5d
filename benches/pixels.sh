#!/usr/bin/env bash
# Every picture costs its pixels (issue 37, item 4): the issue's table,
# side by side in one run. Each row is run with the base binary and the
# new one, interleaved run by run (base, new, base, new, ...) so that the
# load of a shared machine hits both alike, beside the one-segment floor
# at the same size (the same command drawing `axiom F` at depth 0, also
# interleaved). Whole process, from GNU time: CPU seconds (user + sys),
# wall seconds, peak RSS; medians of RUNS runs (default 3). The load
# average (1 minute) is read before each row's runs and printed beside
# its figures. Each row also checks that both binaries wrote the same
# bytes.
#
# Then: `--exact` 1.24a depth 11 at 2048 px against its bounding pass
# (`stats` of the same word), and the two-thread speed-up of the same
# exact render (`--threads 1` against `--threads 2`, interleaved), with
# the load it was measured under.
#
#   benches/pixels.sh BASE NEW        # e.g. /tmp/pixels-base/stlc target/release/stlc
#   RUNS=5 benches/pixels.sh BASE NEW
#
# Output: markdown tables for docs/performance.md.
set -euo pipefail
cd "$(dirname "$0")/.."
BASE=$(realpath "$1")
NEW=$(realpath "$2")
RUNS=${RUNS:-3}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

# Inputs the examples do not hold: 2 million `F+` (every stroke on one
# square) and the one-segment floor.
python3 -c "
import sys
open(sys.argv[1], 'w').write('axiom ' + 'F+' * 2000000 + '\nangle 90\n')" "$OUT/fplus.lsys"
printf 'axiom F\nangle 90\n' >"$OUT/floor.lsys"

median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
load() { cut -d' ' -f1 /proc/loadavg; }

# one OUTFILE BIN ARGS... -> "cpu wall rss_kb"
one() {
    local out=$1 bin=$2
    shift 2
    /usr/bin/time -o "$OUT/time" -f "TIME %U %S %e %M" "$bin" "$@" >/dev/null 2>&1 ||
        { echo "fail fail fail"; return; }
    awk '/^TIME/ {printf "%.2f %.2f %d\n", $2 + $3, $4, $5}' "$OUT/time"
    : "$out"
}

# row LABEL FLOOR_ARGS -- ARGS...: base, new and the floor, interleaved.
row() {
    local label=$1 floor=$2
    shift 3
    local l i r
    l=$(load)
    : >"$OUT/b" && : >"$OUT/n" && : >"$OUT/f"
    for i in $(seq "$RUNS"); do
        one x "$BASE" render "$@" -o "$OUT/b.png" >>"$OUT/b"
        one x "$NEW" render "$@" -o "$OUT/n.png" >>"$OUT/n"
        # shellcheck disable=SC2086
        one x "$NEW" render "$OUT/floor.lsys" --depth 0 $floor -o "$OUT/f.png" >>"$OUT/f"
    done
    local same=yes
    cmp -s "$OUT/b.png" "$OUT/n.png" || same=NO
    col() { awk -v c="$2" '{print $c}' "$OUT/$1" | median; }
    local bc nc fc
    bc=$(col b 1) nc=$(col n 1) fc=$(col f 1)
    printf '| %s | %s | %s s | %s s | %s s | %s / %s KB | %s s | %s | %s / %s | %s |\n' \
        "$label" "$l" "$bc" "$nc" "$(col b 2) / $(col n 2)" "$(col b 3)" "$(col n 3)" "$fc" \
        "$(awk -v a="$bc" -v b="$nc" 'BEGIN { printf "%.2fx", a / b }')" \
        "$(awk -v a="$bc" -v f="$fc" 'BEGIN { printf "%.0fx", a / (f > 0 ? f : 0.005) }')" \
        "$(awk -v a="$nc" -v f="$fc" 'BEGIN { printf "%.0fx", a / (f > 0 ? f : 0.005) }')" "$same"
}

echo "runs: $RUNS; load before: $(cut -d' ' -f1-3 /proc/loadavg); $(nproc) cores"
echo
echo "| render | load | CPU base | CPU new | wall base / new | peak RSS base / new | floor CPU | new speed-up | times the floor (base / new) | same bytes |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |"
row "1.24b depth 30, default size" "" -- examples/abop-1.24b.lsys --depth 30
row "1.24b depth 30, 2048 px" "--size 2048x2048" -- examples/abop-1.24b.lsys --depth 30 --size 2048x2048
row "1.24a depth 57, 2048 px" "--size 2048x2048" -- examples/abop-1.24a.lsys --depth 57 --size 2048x2048
row "Hilbert depth 30, 2048 px" "--size 2048x2048" -- examples/hilbert.lsys --depth 30 --size 2048x2048
row "2 million F+, default size" "" -- "$OUT/fplus.lsys" --depth 0
row "--exact 1.24a depth 11, 2048 px" "--size 2048x2048" -- examples/abop-1.24a.lsys --exact --depth 11 --size 2048x2048
echo

# The exact path against its bounding pass, and two threads against one
# (new binary), interleaved.
EX=(examples/abop-1.24a.lsys --exact --depth 11 --size 2048x2048)
l=$(load)
: >"$OUT/s" && : >"$OUT/t1" && : >"$OUT/t2"
for i in $(seq "$RUNS"); do
    one x "$NEW" stats examples/abop-1.24a.lsys --depth 11 --json >>"$OUT/s"
    one x "$NEW" render "${EX[@]}" --threads 1 -o "$OUT/t1.png" >>"$OUT/t1"
    one x "$NEW" render "${EX[@]}" --threads 2 -o "$OUT/t2.png" >>"$OUT/t2"
done
same=yes
cmp -s "$OUT/t1.png" "$OUT/t2.png" || same=NO
col() { awk -v c="$2" '{print $c}' "$OUT/$1" | median; }
echo "| --exact 1.24a depth 11, 2048 px (new) | load | CPU | wall | peak RSS |"
echo "| --- | ---: | ---: | ---: | ---: |"
echo "| bounding pass (\`stats\` of the same word) | $l | $(col s 1) s | $(col s 2) s | $(col s 3) KB |"
echo "| \`--threads 1\` | $l | $(col t1 1) s | $(col t1 2) s | $(col t1 3) KB |"
echo "| \`--threads 2\` | $l | $(col t2 1) s | $(col t2 2) s | $(col t2 3) KB |"
echo
echo "two threads: $(awk -v a="$(col t1 2)" -v b="$(col t2 2)" 'BEGIN { printf "%.2fx", a / b }') the wall time of one (same bytes: $same); load during: $l, after: $(cut -d' ' -f1-3 /proc/loadavg)"
