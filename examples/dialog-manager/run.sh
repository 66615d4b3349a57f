#!/usr/bin/env bash
# Runs the example dialog manager in its own virtual environment, made on first use (and again
# when requirements.txt changes). Arguments go to dm.py; see README.md. `--install-only`
# prepares the environment and exits.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
venv="$here/.venv"
if ! cmp -s "$here/requirements.txt" "$venv/requirements.installed" 2>/dev/null ||
  ! "$venv/bin/python" -c '' >/dev/null 2>&1; then
  echo "dm: installing websockets into $venv" >&2
  rm -rf "$venv"
  python3 -m venv "$venv"
  "$venv/bin/python" -m pip install --quiet --disable-pip-version-check --no-input -r "$here/requirements.txt"
  cp "$here/requirements.txt" "$venv/requirements.installed"
fi
# scripts/install-test-deps.sh only prepares the environment.
[ "${1:-}" = "--install-only" ] && exit 0
exec "$venv/bin/python" "$here/dm.py" "$@"
