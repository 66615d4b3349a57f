#!/usr/bin/env bash
# Installs what Docent's tests need from Debian, only when it is missing (idempotent):
#   espeak-ng  real speech synthesis, verified through WAV output on machines without sound.
# Runs as root or through sudo. Called by scripts/test.sh; safe to run by hand.
set -euo pipefail

packages=()
command -v espeak-ng >/dev/null 2>&1 || packages+=(espeak-ng)

if [ ${#packages[@]} -eq 0 ]; then
  exit 0
fi

as_root() {
  if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi
}

echo "installing test dependencies: ${packages[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
as_root apt-get update -qq
as_root apt-get install -y -qq --no-install-recommends "${packages[@]}" >/dev/null
