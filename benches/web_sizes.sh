#!/bin/sh
# The paper's claim (003, section VI: a tree described in STL is far
# smaller than its picture), measured for every example: bytes of the
# source, of its BED (an OD grown; a BED is its own; an L-system has
# none), of the SVG and of the PNG at the gallery's size (docs/gallery/
# make.sh's sizes and --show-layout, each file's own depth and seed), each
# also gzipped (gzip -9 -n); and the WebAssembly module's size. Prints a
# Markdown table (docs/web.md). Run from the repository root after
# `cargo build --release` and the README's `## On the web` build.
set -eu
cd "$(dirname "$0")/.."
B=target/release/stlc
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
gz() { gzip -9 -n -c "$1" | wc -c | tr -d ' '; }
size() { wc -c <"$1" | tr -d ' '; }

echo "| example | source | gz | BED | gz | SVG | gz | PNG | gz | PNG / source (gz) |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
for f in examples/*.od examples/*.bed examples/*.lsys; do
  n=$(basename "$f")
  case "$n" in
    2dtree.od) opts="--show-layout --size 360x384" ;;
    fig9.od) opts="--show-layout --size 300x316" ;;
    alternatives.od) opts="--show-layout --size 240x300" ;;
    decrement.od) opts="--size 300x300" ;;
    *.od | *.bed) opts="--show-layout --size 300x300" ;;
    *.lsys) opts="--size 240x240" ;;
  esac
  # shellcheck disable=SC2086
  $B render "$f" $opts -f svg -o "$tmp/t.svg" 2>/dev/null
  # shellcheck disable=SC2086
  $B render "$f" $opts -f png -o "$tmp/t.png" 2>/dev/null
  case "$n" in
    *.od) $B compile "$f" -o "$tmp/t.bed" 2>/dev/null; bed="$(size "$tmp/t.bed") | $(gz "$tmp/t.bed")" ;;
    *.bed) bed="$(size "$f") | $(gz "$f")" ;;
    *) bed="- | -" ;;
  esac
  ratio=$(awk "BEGIN { printf \"%.0f\", $(gz "$tmp/t.png") / $(gz "$f") }")
  echo "| \`$n\` | $(size "$f") | $(gz "$f") | $bed | $(size "$tmp/t.svg") | $(gz "$tmp/t.svg") | $(size "$tmp/t.png") | $(gz "$tmp/t.png") | $ratio |"
done
w=target/site/stlc.wasm
if [ -f "$w" ]; then
  echo
  echo "WebAssembly module ($w): $(size "$w") bytes, $(gz "$w") gzipped"
fi
