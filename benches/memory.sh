#!/usr/bin/env bash
# Peak memory per input byte on the hostile and large inputs of
# docs/limits.md ("Memory per input byte"). Builds the inputs in a temporary
# folder, runs the release binary on each and prints bytes, wall time, peak
# RSS and RSS per input byte.
#
#   benches/memory.sh [path/to/stlc]
#
# Needs python3 (to write the inputs) and GNU time (/usr/bin/time).
set -euo pipefail
BIN=${1:-target/release/stlc}
[ -x "$BIN" ] || { echo "build first: cargo build --release" >&2; exit 1; }
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT

python3 - "$T" <<'PY'
import sys
t = sys.argv[1]
head = "T\n(0,0)\nL=10(0) B=1(0) A=30\nRULE\n"
def w(name, rules, seed, tail=""):
    with open(f"{t}/{name}", "w") as f:
        f.write(head + rules + "SEED\n" + seed + "\nENDSEED\n" + tail)
# Drawing only.
w("flat-draw.bed", "R1: [+F][-F]\n", "F+F-" * 3_000_000)
# A million leaf terms, no spaces; the same one a line.
w("terms.bed", "R1: [+F][-F]\n", "R1{,}" * 1_000_000)
w("terms-lines.bed", "R1: [+F][-F]\n", "R1{,}\n" * 1_000_000)
# A full binary tree of terms, depth 19 (about a million terms).
def tree(d):
    out = []
    stack = [d]
    # Iterative pre-order writer: `R1{` child `,` child `}`.
    todo = [("open", d)]
    while todo:
        k, v = todo.pop()
        if k == "lit":
            out.append(v)
        elif v == 0:
            out.append("R1{,}")
        else:
            out.append("R1{")
            todo.append(("lit", "}"))
            todo.append(("open", v - 1))
            todo.append(("lit", ","))
            todo.append(("open", v - 1))
    return "".join(out)
w("binary.bed", "R1: [+F][-F]\n", tree(19))
# Chains of a one-branch rule, 9,000 deep (under --max-nesting), 200 of them.
chain = "A{" * 9000 + "}" * 9000
w("chains.bed", "A: [F]\n", "\n".join([chain] * 200))
# Bare names (a BED reads `A` as `A{}`): two bytes a term.
w("bare.bed", "A: F\n", "A " * 2_000_000)
# One rule body of megabytes; a RULE section at --max-rule-parts.
w("body.bed", "R1: " + "F+F-" * 1_500_000 + "\n", "R1{}")
w("rules-limit.bed", "".join(f"R{i}: [F]\n" for i in range(49_999)), "F")
# The same terms in an OD, refused by --max-stems before growing.
with open(f"{t}/terms.od", "w") as f:
    f.write(head + "R1: [+F][-F]\nSEED\n" + "R1{,}" * 1_000_000 + "\nENDSEED\n")
# A polygon of a million points, refused by --max-layout-vertices.
pts = ",".join(f"({i % 1000},{i // 1000})" for i in range(1_000_000))
with open(f"{t}/polygon.od", "w") as f:
    f.write(head + "R1: [+F][-F]\nSEED\nR1\nENDSEED\nLAYOUT\n(clGreen) Polygon " + pts + "\nENDLAYOUT\n")
PY

printf '%-16s %-8s %10s %8s %10s %8s\n' input command bytes wall peak_KB B/B
run() {
    local file=$1; shift
    local bytes; bytes=$(stat -c %s "$T/$file")
    local o
    o=$(/usr/bin/time -f "%e %M" "$BIN" "$@" "$T/$file" -o "$T/out.png" 2>&1 >/dev/null | tail -1) || true
    local wall=${o% *} kb=${o#* }
    printf '%-16s %-8s %10d %8s %10s %8.1f\n' "$file" "$1" "$bytes" "$wall" "$kb" \
        "$(echo "$kb * 1024 / $bytes" | bc -l)"
}
checkrun() {
    local file=$1
    local bytes; bytes=$(stat -c %s "$T/$file")
    local o
    o=$(/usr/bin/time -f "%e %M" "$BIN" check "$T/$file" 2>&1 >/dev/null | tail -1) || true
    local wall=${o% *} kb=${o#* }
    printf '%-16s %-8s %10d %8s %10s %8.1f\n' "$file" check "$bytes" "$wall" "$kb" \
        "$(echo "$kb * 1024 / $bytes" | bc -l)"
}
for f in flat-draw.bed terms.bed terms-lines.bed binary.bed chains.bed bare.bed; do
    run "$f" render
done
checkrun body.bed
checkrun rules-limit.bed
checkrun terms.od
checkrun polygon.od
