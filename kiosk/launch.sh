#!/usr/bin/env bash
# Starts Docent's touchscreen page and projector page in Chromium kiosk mode, one browser per
# display, each under its own watchdog (kiosk/watchdog.sh) that restarts it if it exits.
# Docent itself must already run (docent.service); this script waits for its /healthz first.
# Each watchdog also asks Docent every few seconds whether its page is connected
# (/healthz?role=kiosk&name=NAME), and restarts a browser whose tab crashed or hung.
# Step-by-step set-up: docs/DEVICE.md.
#
#   kiosk/launch.sh [--dry-run] [--url URL] [--kiosk-name NAME] [--no-projector] [--state-dir DIR]
#   kiosk/launch.sh --camera-policy [--url URL]
#
# Options (each also settable by the environment variable in brackets):
#   --url URL                   Docent's address [DOCENT_URL] (http://127.0.0.1:8080)
#   --kiosk-name NAME           the name both pages say hello with, shown on the operator
#                               console [KIOSK_NAME] (this computer's host name): 1 to 40
#                               letters, digits, ".", "_" or "-", starting with a letter or digit
#   --touch-position X,Y        touchscreen window position [TOUCH_POSITION] (0,0)
#   --touch-size W,H            touchscreen window size [TOUCH_SIZE] (1280,800)
#   --projector-position X,Y    projector window position [PROJECTOR_POSITION] (1280,0)
#   --projector-size W,H        projector window size [PROJECTOR_SIZE] (1920,1080)
#   --no-projector              touchscreen only, for a kiosk PC with one display [PROJECTOR=0]
#   --state-dir DIR             browser profiles and logs [DOCENT_KIOSK_STATE]
#                               (${XDG_STATE_HOME:-~/.local/state}/docent-kiosk)
#   --chromium PATH             the browser [CHROMIUM] (chromium, chromium-browser or google-chrome)
#   --wait SECONDS              how long to wait for Docent's /healthz [HEALTH_TIMEOUT] (120)
#   --camera-permission MODE    how the touchscreen may use camera and microphone without a
#                               prompt (for the operator's live view) [CAMERA_PERMISSION] (switch):
#                               switch: --auto-accept-camera-and-microphone-capture;
#                               policy: a Chromium managed policy (see --camera-policy)
#   --camera-policy             print that managed policy for URL's origin, then exit
#   --dry-run                   print the commands instead of running them
# More environment:
#   DISABLE_FEATURES=A,B        extra Chromium features to disable (merged into the one switch)
#   CHROMIUM_FLAGS='--x --y'    extra Chromium switches (split on spaces)
#   WATCHDOG_*                  back-off and page-check settings, see kiosk/watchdog.sh
set -euo pipefail

here=$(cd -- "$(dirname -- "${BASH_SOURCE[0]}")" && pwd)

# Clears the crash markers in a Chromium profile so the next start shows no "Restore pages?"
# bubble. Run by the watchdog before every start (also after a crash). Internal helper.
if [[ ${1:-} == --clear-crash-flags ]]; then
    prefs="${2:?--clear-crash-flags needs a profile folder}/Default/Preferences"
    if [[ -f $prefs ]]; then
        sed -i -e 's/"exited_cleanly": *false/"exited_cleanly":true/g' \
            -e 's/"exit_type": *"[A-Za-z_]*"/"exit_type":"Normal"/g' -- "$prefs"
    fi
    exit 0
fi

# Asks Docent at URL whether a page of ROLE named NAME is connected, for the watchdog's
# --alive (`--page-connected URL ROLE NAME`): exit 0 when it is (HTTP 200), 1 when it is not
# (503), 2 when that cannot be told (Docent unreachable, any other answer). Internal helper.
if [[ ${1:-} == --page-connected ]]; then
    probe="${2:?--page-connected needs URL ROLE NAME}/healthz?role=${3:?}&name=${4:?}"
    code=$(curl --silent --output /dev/null --max-time 2 --write-out '%{http_code}' -- "$probe") || true
    case $code in
        200) exit 0 ;;
        503) exit 1 ;;
        *) exit 2 ;;
    esac
fi

url=${DOCENT_URL:-http://127.0.0.1:8080}
kiosk_name=${KIOSK_NAME:-}
touch_position=${TOUCH_POSITION:-0,0}
touch_size=${TOUCH_SIZE:-1280,800}
projector_position=${PROJECTOR_POSITION:-1280,0}
projector_size=${PROJECTOR_SIZE:-1920,1080}
projector=${PROJECTOR:-1}
state_dir=${DOCENT_KIOSK_STATE:-${XDG_STATE_HOME:-${HOME:?HOME is not set}/.local/state}/docent-kiosk}
chromium=${CHROMIUM:-}
health_timeout=${HEALTH_TIMEOUT:-120}
camera_permission=${CAMERA_PERMISSION:-switch}
camera_policy=0
dry_run=0

usage() {
    sed -n '9,34p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//' >&2
    exit 2
}

while (($# > 0)); do
    case $1 in
        --url) url=${2:?--url needs a value}; shift 2 ;;
        --kiosk-name) kiosk_name=${2:?--kiosk-name needs a value}; shift 2 ;;
        --touch-position) touch_position=${2:?}; shift 2 ;;
        --touch-size) touch_size=${2:?}; shift 2 ;;
        --projector-position) projector_position=${2:?}; shift 2 ;;
        --projector-size) projector_size=${2:?}; shift 2 ;;
        --no-projector) projector=0; shift ;;
        --state-dir) state_dir=${2:?}; shift 2 ;;
        --chromium) chromium=${2:?}; shift 2 ;;
        --wait) health_timeout=${2:?}; shift 2 ;;
        --camera-permission) camera_permission=${2:?}; shift 2 ;;
        --camera-policy) camera_policy=1; shift ;;
        --dry-run) dry_run=1; shift ;;
        -h | --help) usage ;;
        *) echo "launch.sh: unknown option $1" >&2; usage ;;
    esac
done

url=${url%/}
for pair in "$touch_position" "$touch_size" "$projector_position" "$projector_size"; do
    [[ $pair =~ ^-?[0-9]+,-?[0-9]+$ ]] || { echo "launch.sh: '$pair' is not of the form X,Y or W,H" >&2; exit 2; }
done
[[ $health_timeout =~ ^[0-9]+$ ]] || { echo "launch.sh: --wait needs whole seconds" >&2; exit 2; }
[[ $camera_permission == switch || $camera_permission == policy ]] ||
    { echo "launch.sh: --camera-permission is switch or policy, not '$camera_permission'" >&2; exit 2; }
[[ $url =~ ^(https?://[^/?#]+) ]] || { echo "launch.sh: '$url' is not an http(s) address" >&2; exit 2; }
origin=${BASH_REMATCH[1]}
# The pages' name (static/client-name.js takes the same, and more); no character in it needs
# quoting in a URL. The host name's first label by default, cut to fit.
name_pattern='^[A-Za-z0-9][A-Za-z0-9._-]{0,39}$'
if [[ -z $kiosk_name ]]; then
    kiosk_name=$(hostname 2>/dev/null || true)
    kiosk_name=${kiosk_name%%.*}
    kiosk_name=${kiosk_name:0:40}
    [[ $kiosk_name =~ $name_pattern ]] || kiosk_name=kiosk
fi
[[ $kiosk_name =~ $name_pattern ]] ||
    { echo "launch.sh: --kiosk-name '$kiosk_name' is not 1 to 40 letters, digits, '.', '_' or '-' (starting with a letter or digit)" >&2; exit 2; }

# ---- Camera and microphone for the operator's live view ----------------------------------------
# The touchscreen page answers the operator console's camera calls (operator.camera: webrtc in
# docent.yaml) with getUserMedia, which must never show a permission prompt on a kiosk. Either
# the switch below (this browser only; not one of the switches Chromium warns about) or a
# managed policy that allows exactly Docent's origin (the port counts); the projector gets
# neither. Chromium offers the camera only to secure pages: https, or http on 127.0.0.1/localhost.
if ((camera_policy)); then
    cat <<EOF
{
  "VideoCaptureAllowedUrls": ["$origin"],
  "AudioCaptureAllowedUrls": ["$origin"]
}
EOF
    exit 0
fi
camera_switches=()
if [[ $camera_permission == switch ]]; then
    camera_switches=(--auto-accept-camera-and-microphone-capture)
elif ! grep -qsF "\"$origin\"" /etc/chromium/policies/managed/*.json /etc/opt/chrome/policies/managed/*.json; then
    echo "launch.sh: no managed Chromium policy allows the camera for $origin;" \
        "the kiosk may ask visitors for permission (docs/DEVICE.md, camera)" >&2
fi

if [[ -z $chromium ]]; then
    for candidate in chromium chromium-browser google-chrome; do
        if command -v "$candidate" >/dev/null 2>&1; then chromium=$(command -v "$candidate"); break; fi
    done
    if [[ -z $chromium ]]; then
        if ((dry_run)); then
            chromium=chromium
        else
            echo "launch.sh: Chromium not found; install it (apt-get install chromium) or set CHROMIUM" >&2
            exit 1
        fi
    fi
fi

# Quotes one word for a shell, leaving plain words (letters, digits, _@%+=:,./-) bare.
quote() {
    if [[ $1 =~ ^[A-Za-z0-9_@%+=:,./-]+$ ]]; then
        printf '%s' "$1"
    else
        printf "'%s'" "${1//\'/\'\\\'\'}"
    fi
}

# Prints a command in a form that can be pasted into a shell (with --long: one switch a line).
show() {
    local long=0 first=1 word
    if [[ $1 == --long ]]; then long=1; shift; fi
    for word in "$@"; do
        if ((first)); then
            first=0
        elif ((long)) && [[ $word == -* ]]; then
            printf ' \\\n    '
        else
            printf ' '
        fi
        quote "$word"
    done
    printf '\n'
}

# Runs a command, or only prints it with --dry-run.
run() {
    if ((dry_run)); then show "$@"; else "$@"; fi
}

# ---- Screen blanking and power saving off --------------------------------------------------
if [[ -n ${DISPLAY:-} ]] && command -v xset >/dev/null 2>&1; then
    run xset s off -dpms s noblank || echo "launch.sh: xset failed; the screens may still blank" >&2
elif [[ -n ${WAYLAND_DISPLAY:-} ]]; then
    echo "launch.sh: Wayland session: turn screen blanking off in the compositor (docs/DEVICE.md)" >&2
elif [[ -z ${DISPLAY:-} ]]; then
    echo "launch.sh: DISPLAY is not set; the browsers need a graphical session (docs/DEVICE.md)" >&2
fi

# ---- Wait for Docent ------------------------------------------------------------------------
health="$url/healthz"
if command -v curl >/dev/null 2>&1; then
    probe=(curl --silent --fail --output /dev/null --max-time 2 "$health")
elif command -v wget >/dev/null 2>&1; then
    probe=(wget --quiet --output-document=/dev/null --timeout=2 --tries=1 "$health")
else
    probe=()
    echo "launch.sh: neither curl nor wget found; not waiting for Docent" >&2
fi
if ((${#probe[@]} > 0)); then
    if ((dry_run)); then
        echo "# wait up to ${health_timeout} s, once a second, until this succeeds:"
        show "${probe[@]}"
    else
        waited=0
        until "${probe[@]}"; do
            if ((waited == 0)); then
                echo "launch.sh: waiting for Docent at $health (up to ${health_timeout} s)" >&2
            fi
            if ((waited >= health_timeout)); then
                echo "launch.sh: Docent did not answer at $health within ${health_timeout} s." >&2
                echo "launch.sh: is it running? systemctl status docent; journalctl -u docent" >&2
                exit 1
            fi
            sleep 1
            waited=$((waited + 1))
        done
    fi
fi

# ---- Chromium switches ------------------------------------------------------------------------
# Chromium honours --disable-features only once (a second switch replaces the first), so all
# disabled features go into this one list. WebRtcHideLocalIpsWithMdns: the touchscreen offers the
# operator's camera call its real network addresses instead of random .local names, so the call
# needs no multicast DNS on the network (the projector makes no such calls).
disabled="TranslateUI,Translate,OverscrollHistoryNavigation,MediaRouter,WebRtcHideLocalIpsWithMdns${DISABLE_FEATURES:+,$DISABLE_FEATURES}"
common=(
    --kiosk
    --noerrdialogs
    --disable-infobars
    --disable-session-crashed-bubble
    --hide-crash-restore-bubble
    --no-first-run
    --no-default-browser-check
    --disable-translate
    --disable-pinch
    --overscroll-history-navigation=0
    --autoplay-policy=no-user-gesture-required
    --touch-events=enabled
    --check-for-update-interval=31536000
    --password-store=basic
    "--disable-features=$disabled"
)
if [[ -n ${CHROMIUM_FLAGS:-} ]]; then
    read -r -a extra <<<"$CHROMIUM_FLAGS"
    common+=("${extra[@]}")
fi

# Whether a page is connected is asked with curl (--page-connected); without curl the
# watchdogs restart a browser only when it exits.
alive_check=0
if command -v curl >/dev/null 2>&1; then
    alive_check=1
else
    echo "launch.sh: curl not found; a browser whose tab crashed is not restarted (apt-get install curl)" >&2
fi

# The watchdog command for one browser: ROLE POSITION SIZE PAGE CLIENT-ROLE [SWITCH...].
browser_command() {
    local role=$1 position=$2 size=$3 page=$4 client_role=$5 profile alive=()
    shift 5
    profile="$state_dir/$role"
    if ((alive_check)); then
        alive=(--alive "$(show "$here/launch.sh" --page-connected "$url" "$client_role" "$kiosk_name")")
    fi
    cmd=(
        "$here/watchdog.sh" --name "$role"
        --before "$(show "$here/launch.sh" --clear-crash-flags "$profile")"
        "${alive[@]}"
        -- "$chromium" "${common[@]}" "$@"
        "--user-data-dir=$profile"
        "--window-position=$position"
        "--window-size=$size"
        "$page"
    )
}

run mkdir -p -- "$state_dir/touch"
((projector == 0)) || run mkdir -p -- "$state_dir/projector"

browser_command touch "$touch_position" "$touch_size" "$url/?kiosk=$kiosk_name" kiosk "${camera_switches[@]}"
touch_cmd=("${cmd[@]}")
projector_cmd=()
if ((projector != 0)); then
    browser_command projector "$projector_position" "$projector_size" "$url/projector?projector=$kiosk_name" projector
    projector_cmd=("${cmd[@]}")
fi

if ((dry_run)); then
    echo "# run in the background, each until stopped:"
    show --long "${touch_cmd[@]}"
    ((${#projector_cmd[@]} == 0)) || show --long "${projector_cmd[@]}"
    exit 0
fi

# ---- Run both watchdogs; stop both if one ends or we are stopped ------------------------------
pids=()
# shellcheck disable=SC2317  # called from the traps
cleanup() {
    trap - TERM INT EXIT
    local pid
    for pid in "${pids[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done
    wait || true
}
trap 'cleanup; exit 0' TERM INT
trap cleanup EXIT

"${touch_cmd[@]}" &
pids+=($!)
if ((${#projector_cmd[@]} > 0)); then
    "${projector_cmd[@]}" &
    pids+=($!)
fi
status=0
wait -n || status=$?
echo "launch.sh: a watchdog ended (status $status); stopping the other browser" >&2
exit 1
