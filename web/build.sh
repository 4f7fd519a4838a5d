#!/bin/sh
# Builds the static Tree Maker into target/site/ (docs/web.md): the page
# of `stlc serve` (src/serve/page, the same modules) with the WebAssembly
# engine (web/page), the module itself, every example and the <stl-tree>
# element. Run from anywhere; needs the wasm32-unknown-unknown target
# (`rustup target add wasm32-unknown-unknown`). Serve the result with any
# static file server: python3 -m http.server -d target/site
#
# Usage: sh web/build.sh [FOLDER]   (default target/site)
#
# It builds into a fresh folder beside FOLDER and then swaps it in, so a
# second build (one after the other, or two at once) never meets a
# half-removed site, and a server showing FOLDER sees the old site or the
# new one, whole.
set -eu
cd "$(dirname "$0")/.."

cargo build -p stlc-web --profile web --target wasm32-unknown-unknown --locked

final=${1:-target/site}
final=${final%/}
mkdir -p "$(dirname "$final")"
site=$(mktemp -d "$final.new.XXXXXX")
trap 'rm -rf "$site"' EXIT
chmod 755 "$site"
mkdir -p "$site/examples" "$site/templates"
cp -R src/serve/page/. "$site/"
cp -R web/page/. "$site/"
cp "${CARGO_TARGET_DIR:-target}/wasm32-unknown-unknown/web/stlc_web.wasm" "$site/stlc.wasm"

# The page itself, as stlc serve serves it: its paths are relative (the
# site may live in a folder) and it names one entry module, entry.js,
# which web/page/entry.js replaced above with the static site's (the
# WebAssembly engine): the HTML is copied, never rewritten.
if ! grep -q 'src="entry.js"' "$site/index.html" || ! grep -q 'href="style.css"' "$site/index.html"; then
  echo "web/build.sh: src/serve/page/index.html must load entry.js and style.css by relative paths" >&2
  exit 1
fi

# The New menu's files: the templates, then every example, and their list.
cp src/serve/templates/new.od src/serve/templates/new.lsys "$site/templates/"
list=""
for f in examples/*.od examples/*.bed examples/*.lsys; do
  cp "$f" "$site/examples/"
  list="$list\"$(basename "$f")\","
done
# Sorted by name, as `stlc serve` lists them.
sorted=$(printf '%s' "$list" | tr ',' '\n' | sed '/^$/d' | LC_ALL=C sort | paste -sd, -)
printf '{"templates": ["new.od", "new.lsys"], "examples": [%s]}\n' "$sorted" >"$site/examples/index.json"

# The swap: rename(2) replaces an empty folder or none, so the old site is
# moved aside first (each build its own name), then the new one takes its
# place; a build swapping in between only makes the rename retry.
bytes=$(wc -c <"$site/stlc.wasm")
old=$(mktemp -d "$final.old.XXXXXX")
trap 'rm -rf "$site" "$old"' EXIT
tries=0
until mv -T "$site" "$final" 2>/dev/null; do
  tries=$((tries + 1))
  if [ "$tries" -gt 20 ]; then
    echo "web/build.sh: cannot put the new site in place at $final (is it a file?)" >&2
    exit 1
  fi
  if [ -d "$final" ]; then
    mv -T "$final" "$old/$tries" 2>/dev/null || true
  elif [ -e "$final" ]; then
    echo "web/build.sh: $final is not a folder: remove it or name another" >&2
    exit 1
  fi
done
trap - EXIT
rm -rf "$old"

echo "built $final ($bytes bytes of WebAssembly)"
