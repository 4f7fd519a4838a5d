#!/bin/sh
# Builds the static Tree Maker into target/site/ (docs/web.md): the page
# of `stlc serve` (src/serve/page, the same modules) with the WebAssembly
# engine (web/page), the module itself, every example and the <stl-tree>
# element. Run from anywhere; needs the wasm32-unknown-unknown target
# (`rustup target add wasm32-unknown-unknown`). Serve the result with any
# static file server: python3 -m http.server -d target/site
set -eu
cd "$(dirname "$0")/.."

cargo build -p stlc-web --profile web --target wasm32-unknown-unknown --locked

site=target/site
rm -rf "$site"
mkdir -p "$site/examples" "$site/templates"
cp -R src/serve/page/. "$site/"
cp -R web/page/. "$site/"
cp "${CARGO_TARGET_DIR:-target}/wasm32-unknown-unknown/web/stlc_web.wasm" "$site/stlc.wasm"

# The page itself: paths relative to it (the site may live in a folder),
# no token (nothing here saves to a server), site.js as the entry module.
sed -e 's|href="/style.css"|href="style.css"|' \
    -e 's|src="/app.js"|src="site.js"|' \
    -e 's|{{TOKEN}}||' \
    src/serve/page/index.html >"$site/index.html"
for want in 'href="style.css"' 'src="site.js"'; do
  if ! grep -q "$want" "$site/index.html"; then
    echo "web/build.sh: src/serve/page/index.html changed: cannot set $want" >&2
    exit 1
  fi
done

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

echo "built $site ($(wc -c <"$site/stlc.wasm") bytes of WebAssembly)"
