#!/usr/bin/env bash
# The whole test suite, as the README and CI run it: installs what the tests need (idempotent),
# then runs every Rust test (unit and integration, against real servers and real espeak-ng).
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-test-deps.sh
cargo test --workspace --locked "$@"
