#!/usr/bin/env bash
# What the level of detail changes: per-pixel difference between the
# default render and `--exact` for the gallery's trees (ABOP 1.24a-f) at
# depths 8..11, the stochastic ABOP 1.27 (default seed) and the curves of
# examples/ at 8..11, 512 x 512 (and whatever SIZE says), with
# examples/pixdiff.rs. The difference of a pixel is its largest channel
# difference; "mean" is over all pixels; "inked" counts pixels at least
# half inked (over 127 from the background). Results go into docs/rendering.md
# (Level of detail) by hand.
#
#   benches/lod-quality.sh                  # builds stlc and pixdiff (release)
#   STLC=target/release/stlc PIXDIFF=target/release/examples/pixdiff SIZE=800x800 benches/lod-quality.sh
#   SIZE=default benches/lod-quality.sh     # no --size: the default (800 on the longer side)
#
# 1.24c is left out past depth 9 (8^10 = 10^9 segments: minutes with --exact),
# 1.24b past 10 with DEPTHS_B (default "8 9 10"; 11 takes 10 s --exact).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ -z "${STLC:-}" ] || [ -z "${PIXDIFF:-}" ]; then
    cargo build --release --bin stlc --example pixdiff >&2
    T=${CARGO_TARGET_DIR:-target}
    STLC=${STLC:-$T/release/stlc}
    PIXDIFF=${PIXDIFF:-$T/release/examples/pixdiff}
fi
SIZE=${SIZE:-512x512}
SZ=(--size "$SIZE")
[ "$SIZE" = default ] && SZ=()
DEPTHS=${DEPTHS:-"8 9 10 11"}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
row() { # name depth t0 t1 t2: one table row from the two PNGs in $OUT
    local mean max n o16 o64 ix il
    read -r _ mean _ max _ n _ o16 _ o64 _ _ _ ix il <<<"$("$PIXDIFF" "$OUT/x.png" "$OUT/l.png" | tr -d '(),:')"
    awk -v t="$1" -v d="$2" -v mean="$mean" -v max="$max" -v n="$n" -v a="$o16" -v b="$o64" \
        -v ix="$ix" -v il="$il" \
        -v xs="$((($4 - $3) / 1000000))" -v ls="$((($5 - $4) / 1000000))" \
        'BEGIN { printf "| %s | %d | %s | %s | %s | %s | %s | %d | %d | %+.1f %% | %.2f | %.2f |\n", t, d, mean, max, n, a, b, ix, il, ix ? 100 * (il - ix) / ix : 0, xs / 1000, ls / 1000 }'
}
echo "| system | depth | mean | max | pixels differing | > 16 | > 64 | inked exact | inked LOD | inked | exact s | LOD s |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
for t in a b c d e f; do
    for d in $DEPTHS; do
        if [ "$t" = c ] && [ "$d" -ge 10 ]; then continue; fi
        if [ "$t" = b ] && ! grep -qw "$d" <<<"${DEPTHS_B:-8 9 10}"; then continue; fi
        f=examples/abop-1.24$t.lsys
        t0=$(date +%s%N)
        "$STLC" render "$f" --depth "$d" "${SZ[@]}" --exact -o "$OUT/x.png" 2>/dev/null
        t1=$(date +%s%N)
        "$STLC" render "$f" --depth "$d" "${SZ[@]}" -o "$OUT/l.png" 2>/dev/null
        t2=$(date +%s%N)
        row "1.24$t" "$d" "$t0" "$t1" "$t2"
    done
done
for curve in "abop-1.27 8 9 10 11" "koch-snowflake 8 9 10 11" "sierpinski-arrowhead 8 9 10 11 12" \
    "hilbert 8 9 10 11" "stl-003-fig4 8 9 10 11"; do
    read -r name ds <<<"$curve"
    for d in $ds; do
        f=examples/$name.lsys
        t0=$(date +%s%N)
        "$STLC" render "$f" --depth "$d" "${SZ[@]}" --exact -o "$OUT/x.png" 2>/dev/null
        t1=$(date +%s%N)
        "$STLC" render "$f" --depth "$d" "${SZ[@]}" -o "$OUT/l.png" 2>/dev/null
        t2=$(date +%s%N)
        row "$name" "$d" "$t0" "$t1" "$t2"
    done
done
