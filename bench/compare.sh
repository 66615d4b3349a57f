#!/usr/bin/env bash
# Runs the shared side-by-side harness (../shared/bench/run.sh: a bare tokio-tungstenite relay,
# the floor; axum; Node ws; Flask-SocketIO) with Docent as one more target, in two
# configurations, and saves each run's RESULTS.md as bench/results/compare-CONFIG-STAMP.md:
#
#   kiosk       bundle bench/bundles/kiosk: OK → DISPLAY_PAGE; wsload's subscribers are kiosks
#   ws-adapter  bundle bench/bundles/ws-adapter: OK → SAY; wsload's subscribers are adapters
#               serving SAY (they never answer `done`, which does not change the latency)
#
# wsload's senders say hello as operators (declining events) in both. The shared folder is never written to: it is
# copied to a scratch folder (COMPARE_DIR, default /tmp/docent-compare) and run there; its Node
# and Python dependencies are installed once into that copy.
#
#   bench/compare.sh                              # ~10 min: two shared runs
#   CONFIGS=kiosk bench/compare.sh                # one configuration
#   ROUNDS=5 TARGETS="raw-tungstenite docent" bench/compare.sh
#
# A regression guard: DOCENT_BEFORE=DIR adds a target `docent-before`, the release binary
# DIR/target/release/docent (a worktree of an older commit, built) serving DIR's own bench
# bundle, interleaved with today's in the same run, so that a change can be told from the
# machine's noise (bench/README.md, "Noise or a cost that crept in?"):
#
#   git worktree add /tmp/before OLD && (cd /tmp/before && cargo build --release --bin docent)
#   DOCENT_BEFORE=/tmp/before CONFIGS=kiosk ROUNDS=5 \
#     TARGETS="raw-tungstenite docent-before docent" bench/compare.sh
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
SHARED=${SHARED_BENCH:-$ROOT/../shared/bench}
SCRATCH=${COMPARE_DIR:-/tmp/docent-compare}
CONFIGS=${CONFIGS:-kiosk ws-adapter}
STAMP=$(date -u +%Y%m%d-%H%M)
[[ -x $SHARED/run.sh ]] || { echo "no shared harness at $SHARED (set SHARED_BENCH)" >&2; exit 1; }

echo "== build Docent (release)" >&2
cargo build --release --quiet -p docent
mkdir -p "$SCRATCH/bench" bench/results
# A copy of the binary, so that a rebuild in the work tree cannot swap it during the run.
cp target/release/docent "$SCRATCH/docent"
tar -C "$SHARED" --exclude=./results --exclude=./RESULTS.md \
  --exclude=./relays/node-ws/node_modules --exclude=./relays/python-socketio/.venv \
  -cf - . | tar -C "$SCRATCH/bench" -xf -
chmod -R u+w "$SCRATCH/bench"
if [[ -n ${DOCENT_BEFORE:-} ]]; then
  [[ -x $DOCENT_BEFORE/target/release/docent ]] || {
    echo "DOCENT_BEFORE: no $DOCENT_BEFORE/target/release/docent (build it there first)" >&2
    exit 1
  }
  cp "$DOCENT_BEFORE/target/release/docent" "$SCRATCH/docent-before"
  # The harness knows one Docent target; the scratch copy learns a second, started by
  # DOCENT_BEFORE_CMD and spoken to like the first.
  sed -i 's/^    docent)$/    docent-before)\n      SERVER=(bash -c "exec ${DOCENT_BEFORE_CMD\/\/\\{port\\}\/$2}")\n      eval "LOAD=(--url \\"\\$url\/ws\\" $DOCENT_LOAD)" ;;\n    docent)/' \
    "$SCRATCH/bench/run.sh"
  grep -q '^    docent-before)$' "$SCRATCH/bench/run.sh" || {
    echo "the shared run.sh changed: cannot add the docent-before target" >&2
    exit 1
  }
fi
export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-/tmp/bench-target}

TRIGGER='{"type":"trigger","label":"{label}","ref":"{ref}"}'
# Senders only trigger, as the floor's do: they decline the event stream an operator gets.
OPERATOR='{"type":"hello","role":"operator","events":false}'
for config in $CONFIGS; do
  case $config in
    kiosk) hello='{"type":"hello","role":"kiosk"}' ;;
    ws-adapter) hello='{"type":"hello","role":"adapter","verbs":["SAY"]}' ;;
    *) echo "unknown configuration: $config (kiosk or ws-adapter)" >&2; exit 1 ;;
  esac
  corpus=$SCRATCH/corpus-$config
  rm -rf "$corpus"
  # The older binary gets no --open: access control came later, and its bundle is its own.
  export DOCENT_BEFORE_CMD="$SCRATCH/docent-before serve ${DOCENT_BEFORE:-}/bench/bundles/$config --listen 127.0.0.1:{port} --corpus $corpus-before"
  export DOCENT_CMD="$SCRATCH/docent serve $ROOT/bench/bundles/$config --listen 127.0.0.1:{port} --open --corpus $corpus"
  # Shell words, eval'd by the shared run.sh.
  export DOCENT_LOAD="--trigger-template '$TRIGGER' --hello '$hello' --sender-hello '$OPERATOR' --match-field ref --match-if type=command"
  echo "== shared harness with Docent, configuration $config" >&2
  "$SCRATCH/bench/run.sh"
  out=bench/results/compare-$config-$STAMP.md
  {
    echo "<!-- bench/compare.sh, configuration $config."
    echo "     docent: $DOCENT_CMD"
    echo "     wsload flags for docent: $DOCENT_LOAD -->"
    echo
    cat "$SCRATCH/bench/RESULTS.md"
  } >"$out"
  cp "$SCRATCH/bench/results/docent.log" "bench/results/compare-$config-$STAMP.docent.log" 2>/dev/null || true
  rm -rf "$corpus" "$corpus-before"
  echo "== saved $out" >&2
done
