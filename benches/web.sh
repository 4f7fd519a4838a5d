#!/bin/sh
# The static site against `stlc serve`, in one headless Chromium, one run
# (docs/web.md): page load to first picture, and edit to picture on
# 2dtree, holes and grove (medians of STLC_WEB_RUNS edits each, default
# 15) with a release `stlc serve` and the site's release WebAssembly
# module; then the compression table (benches/web_sizes.sh).
# Run from the repository root.
set -eu
cd "$(dirname "$0")/.."
cargo build --release --quiet
STLC_SERVE_BIN="$PWD/target/release/stlc" \
  cargo test --quiet --test integration browser_web::measure -- --ignored --nocapture
