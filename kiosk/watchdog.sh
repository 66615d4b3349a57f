#!/usr/bin/env bash
# Runs a command and starts it again whenever it exits, e.g. a kiosk browser that crashed or
# was closed. Used by launch.sh, one watchdog per browser; see docs/DEVICE.md.
#
#   kiosk/watchdog.sh [--name NAME] [--before 'SHELL COMMAND'] -- COMMAND [ARG...]
#
#   --name NAME     label for the log lines (default: the command's file name)
#   --before CMD    shell command run (with bash -c) before every start, e.g. to clear
#                   Chromium's crash flags so no "restore pages" bubble appears; its failure
#                   is logged and does not stop the watchdog
#
# Back-off between starts: 1 s, doubled after each quick exit up to 30 s; a run that lasted
# 60 s or more resets it to 1 s. Tunable through the environment (whole seconds):
#   WATCHDOG_BACKOFF_MIN=1  WATCHDOG_BACKOFF_MAX=30  WATCHDOG_RESET_AFTER=60
#   WATCHDOG_MAX_RESTARTS=0   (0: restart forever; N: give up after N restarts, exit status 1)
#
# Log lines go to stderr (the journal under systemd). SIGTERM or SIGINT stops the command
# and the watchdog (exit status 0).
set -euo pipefail

backoff_min=${WATCHDOG_BACKOFF_MIN:-1}
backoff_max=${WATCHDOG_BACKOFF_MAX:-30}
reset_after=${WATCHDOG_RESET_AFTER:-60}
max_restarts=${WATCHDOG_MAX_RESTARTS:-0}

usage() {
    sed -n '5,10p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//' >&2
    exit 2
}

name=""
before=""
while (($# > 0)); do
    case $1 in
        --name) name=${2:?--name needs a value}; shift 2 ;;
        --before) before=${2:?--before needs a value}; shift 2 ;;
        --) shift; break ;;
        -h | --help) usage ;;
        *) echo "watchdog.sh: unknown option $1 (the command goes after --)" >&2; usage ;;
    esac
done
(($# > 0)) || usage
for n in "$backoff_min" "$backoff_max" "$reset_after" "$max_restarts"; do
    [[ $n =~ ^[0-9]+$ ]] || { echo "watchdog.sh: WATCHDOG_* values must be whole seconds, got '$n'" >&2; exit 2; }
done
((backoff_min >= 1)) || backoff_min=1
name=${name:-$(basename -- "$1")}

log() {
    printf '%s watchdog[%s]: %s\n' "$(date '+%Y-%m-%d %H:%M:%S')" "$name" "$*" >&2
}

child=""
stopping=0
stop() {
    stopping=1
    log "stopping"
    if [[ -n $child ]] && kill -0 "$child" 2>/dev/null; then
        kill -TERM "$child" 2>/dev/null || true
        wait "$child" 2>/dev/null || true
    fi
    exit 0
}
trap stop TERM INT

delay=$backoff_min
restarts=0
while :; do
    if [[ -n $before ]]; then
        bash -c "$before" || log "--before command failed (status $?); starting anyway"
    fi
    started=$SECONDS
    log "starting: $*"
    "$@" &
    child=$!
    status=0
    wait "$child" || status=$?
    child=""
    ((stopping == 0)) || exit 0
    uptime=$((SECONDS - started))
    if ((uptime >= reset_after)); then
        delay=$backoff_min
    fi
    if ((max_restarts > 0 && restarts >= max_restarts)); then
        log "exited with status $status after ${uptime} s; giving up after $restarts restart(s)"
        exit 1
    fi
    restarts=$((restarts + 1))
    log "exited with status $status after ${uptime} s; restart $restarts in ${delay} s"
    sleep "$delay" &
    wait $! || true
    delay=$((delay * 2))
    ((delay <= backoff_max)) || delay=$backoff_max
done
