#!/usr/bin/env bash
# Builds Docent and docent-bench (release), then runs every scenario (adapter, kiosk, max, idle)
# against a fresh Docent each and prints one JSON line per scenario and a table. The output is
# also saved to bench/results/run-latest.txt. Extra arguments go to docent-bench:
#
#   bench/run.sh                 # ~1 min: 10 s measured per scenario, 1,000 idle connections
#   bench/run.sh --quick         # ~15 s
#   bench/run.sh --scenario kiosk --kiosks 100 --rate 50
set -euo pipefail
cd "$(dirname "$0")/.."

echo "== build (release)" >&2
cargo build --release --quiet -p docent -p docent-bench
# 1,000 idle connections need as many descriptors on each side.
ulimit -n 4096 2>/dev/null || echo "== could not raise the open-file limit; idle may fail" >&2
mkdir -p bench/results
./target/release/docent-bench "$@" | tee bench/results/run-latest.txt
