#!/usr/bin/env bash
# The whole test suite, as the README and CI run it: installs what the tests need (idempotent),
# checks formatting and lints (warnings are errors), runs every Rust test (unit and integration, against real servers and real espeak-ng), then the
# browser tests in tests/e2e (headless Chromium against the real docent binary).
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-test-deps.sh
# Idempotent: the components are there on a machine set up with rustup's default profile.
if command -v rustup >/dev/null; then
  rustup component add rustfmt clippy >/dev/null 2>&1 || true
fi
cargo fmt --all --check
cargo clippy --workspace --all-targets --locked -- -D warnings
cargo test --workspace --locked "$@"
# `cargo test` builds the binary for the integration tests already; this only makes sure.
cargo build --locked --quiet --bin docent
DOCENT_BIN="${DOCENT_BIN:-${CARGO_TARGET_DIR:-target}/debug/docent}" node --test tests/e2e/
