#!/usr/bin/env bash
# The long form of the soak test (tests/integration/soak.rs) on the release
# build: 200 slowloris connections, 64 that never read their answers and 8
# heavy renders (4 abandoned after 0.3 s) for SECONDS, while a light client
# measures `GET /` and a small render; then KILLS saves killed with SIGKILL.
# Prints the light answers' p50, p99 and maximum, the server's peak resident
# size, and the saves' outcome (docs/limits.md gives the figures).
#
#   benches/soak.sh [SECONDS] [KILLS]      (defaults: 120 and 60)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-120}"
kills="${2:-60}"
cargo build --release --locked --quiet
STLC_SOAK_BINARY="$PWD/target/release/stlc" STLC_SOAK_SECONDS="$seconds" STLC_SOAK_KILLS="$kills" \
  cargo test --locked --quiet --test integration soak:: -- --nocapture --test-threads 1 2>&1 |
  grep -E "soak [0-9]+ s:|kill runs|test result|panicked"
