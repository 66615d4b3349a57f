#!/usr/bin/env bash
# The ten-minute soak: two hours of a museum's day compressed twelvefold (50 kiosks tapping,
# an operator and a dialog manager triggering, reconnect storms, live reloads, sessions,
# recordings) against the release binary. It is the one-minute soak of the test command
# (tests/soak.rs) run longer: the same load and the same pass rules. Its samples, figures and
# plot go to bench/results/soak-latest.{csv,json,svg}; the verdict is the test's.
#
#   bench/soak.sh          # 10 minutes
#   bench/soak.sh 120      # 2 minutes
set -euo pipefail
cd "$(dirname "$0")/.."
target="${CARGO_TARGET_DIR:-$PWD/target}"

echo "== build (release docent; the load client is the test binary)" >&2
cargo build --release --locked --quiet --bin docent
DOCENT_SOAK_SECONDS="${1:-600}" \
DOCENT_SOAK_BIN="$target/release/docent" \
DOCENT_SOAK_OUT="$PWD/bench/results" \
  cargo test --locked -p docent --test soak -- --nocapture
