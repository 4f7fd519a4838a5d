#!/usr/bin/env bash
# What the 3D level of detail changes (docs/3d.md, *Level of detail*):
# per-pixel difference between the default view and `--exact` of the
# examples' 3D systems, with examples/pixdiff.rs (as lod-quality.sh does
# for 2D: the largest channel difference per pixel, its mean over all
# pixels, pixels differing, and pixels at least half inked in each), and
# the time of each (single runs). Depths where the exact view fits its
# 10^7-stem limit.
#
#   benches/lod3d-quality.sh               # builds stlc and pixdiff (release)
#   STLC=target/release/stlc PIXDIFF=target/release/examples/pixdiff SIZE=512x512 benches/lod3d-quality.sh
set -euo pipefail
cd "$(dirname "$0")/.."
if [ -z "${STLC:-}" ] || [ -z "${PIXDIFF:-}" ]; then
    cargo build --release --bin stlc --example pixdiff >&2
    T=${CARGO_TARGET_DIR:-target}
    STLC=${STLC:-$T/release/stlc}
    PIXDIFF=${PIXDIFF:-$T/release/examples/pixdiff}
fi
SIZE=${SIZE:-800x800}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
echo "| system | depth | view | mean | max | pixels differing | > 16 | > 64 | inked exact | inked LOD | exact s | LOD s |"
echo "| --- | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
IFS=";" read -r -a CASES <<<"${CASES:-plant3d-bare 10 11 12 13 14;hilbert3d 5 6 7}"
for case in "${CASES[@]}"; do
    read -r name ds <<<"$case"
    for d in $ds; do
        for view in 30,20 120,60; do
            f=examples/$name.lsys
            t0=$(date +%s%N)
            "$STLC" render "$f" --depth "$d" --view "$view" --size "$SIZE" --exact -o "$OUT/x.png" 2>/dev/null
            t1=$(date +%s%N)
            "$STLC" render "$f" --depth "$d" --view "$view" --size "$SIZE" -o "$OUT/l.png" 2>/dev/null
            t2=$(date +%s%N)
            read -r _ mean _ max _ n _ o16 _ o64 _ _ _ ix il <<<"$("$PIXDIFF" "$OUT/x.png" "$OUT/l.png" | tr -d '(),:')"
            awk -v t="$name" -v d="$d" -v v="$view" -v mean="$mean" -v max="$max" -v n="$n" -v a="$o16" -v b="$o64" \
                -v ix="$ix" -v il="$il" -v xs="$(((t1 - t0) / 1000000))" -v ls="$(((t2 - t1) / 1000000))" \
                'BEGIN { printf "| %s | %d | %s | %s | %s | %s | %s | %s | %d | %d | %.2f | %.2f |\n", t, d, v, mean, max, n, a, b, ix, il, xs / 1000, ls / 1000 }'
        done
    done
done
