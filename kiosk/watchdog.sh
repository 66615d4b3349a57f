#!/usr/bin/env bash
# Runs a command and starts it again whenever it exits, e.g. a kiosk browser that crashed or
# was closed; with --alive also when it still runs but its page is dead (a crashed tab). Used
# by launch.sh, one watchdog per browser; see docs/DEVICE.md.
#
#   kiosk/watchdog.sh [--name NAME] [--before 'SHELL COMMAND'] [--alive 'SHELL COMMAND'] -- COMMAND [ARG...]
#
#   --name NAME     label for the log lines (default: the command's file name)
#   --before CMD    shell command run (with bash -c) before every start, e.g. to clear
#                   Chromium's crash flags so no "restore pages" bubble appears; its failure
#                   is logged and does not stop the watchdog
#   --alive CMD     shell command (bash -c) asking whether the command's page is alive, run
#                   every WATCHDOG_ALIVE_EVERY s once WATCHDOG_ALIVE_GRACE s passed since each
#                   start: exit 0 alive, 1 dead, anything else cannot tell (e.g. Docent is
#                   unreachable: the browser is left alone). After WATCHDOG_ALIVE_FAILS dead
#                   answers in a row the command is stopped (TERM, then KILL after
#                   WATCHDOG_KILL_AFTER s) and started again as after a crash
#
# Back-off between starts: 1 s, doubled after each quick exit up to 30 s; a run that lasted
# 60 s or more resets it to 1 s. Tunable through the environment (whole seconds):
#   WATCHDOG_BACKOFF_MIN=1  WATCHDOG_BACKOFF_MAX=30  WATCHDOG_RESET_AFTER=60
#   WATCHDOG_MAX_RESTARTS=0   (0: restart forever; N: give up after N restarts, exit status 1)
#   WATCHDOG_ALIVE_GRACE=20  WATCHDOG_ALIVE_EVERY=5  WATCHDOG_ALIVE_FAILS=3  WATCHDOG_KILL_AFTER=5
#   (an --alive command is given at most 10 s; one that takes longer cannot tell)
#
# Log lines go to stderr (the journal under systemd). SIGTERM or SIGINT stops the command
# and the watchdog (exit status 0).
set -euo pipefail

backoff_min=${WATCHDOG_BACKOFF_MIN:-1}
backoff_max=${WATCHDOG_BACKOFF_MAX:-30}
reset_after=${WATCHDOG_RESET_AFTER:-60}
max_restarts=${WATCHDOG_MAX_RESTARTS:-0}
alive_grace=${WATCHDOG_ALIVE_GRACE:-20}
alive_every=${WATCHDOG_ALIVE_EVERY:-5}
alive_fails=${WATCHDOG_ALIVE_FAILS:-3}
kill_after=${WATCHDOG_KILL_AFTER:-5}

usage() {
    sed -n '6,18p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//' >&2
    exit 2
}

name=""
before=""
alive=""
while (($# > 0)); do
    case $1 in
        --name) name=${2:?--name needs a value}; shift 2 ;;
        --before) before=${2:?--before needs a value}; shift 2 ;;
        --alive) alive=${2:?--alive needs a value}; shift 2 ;;
        --) shift; break ;;
        -h | --help) usage ;;
        *) echo "watchdog.sh: unknown option $1 (the command goes after --)" >&2; usage ;;
    esac
done
(($# > 0)) || usage
for n in "$backoff_min" "$backoff_max" "$reset_after" "$max_restarts" \
    "$alive_grace" "$alive_every" "$alive_fails" "$kill_after"; do
    [[ $n =~ ^[0-9]+$ ]] || { echo "watchdog.sh: WATCHDOG_* values must be whole seconds, got '$n'" >&2; exit 2; }
done
((backoff_min >= 1)) || backoff_min=1
((alive_every >= 1)) || alive_every=1
((alive_fails >= 1)) || alive_fails=1
name=${name:-$(basename -- "$1")}

log() {
    printf '%s watchdog[%s]: %s\n' "$(date '+%Y-%m-%d %H:%M:%S')" "$name" "$*" >&2
}

# Sleeps N seconds in a way a signal's trap can cut short.
nap() {
    sleep "$1" &
    napping=$!
    wait "$napping" || true
}

# Stops process $1: TERM, then KILL if it is still there after $kill_after seconds.
stop_process() {
    local pid=$1 waited=0
    kill -TERM "$pid" 2>/dev/null || return 0
    while kill -0 "$pid" 2>/dev/null; do
        if ((waited >= kill_after)); then
            log "still running ${kill_after} s after TERM; killing it"
            kill -KILL "$pid" 2>/dev/null || true
            return 0
        fi
        nap 1
        waited=$((waited + 1))
    done
}

# Runs in the background beside the command $1 (a process id): asks --alive every
# $alive_every s after the grace, and stops the command after $alive_fails dead answers in a
# row; the main loop then starts it again. "Cannot tell" breaks the row: the page may be fine
# while Docent restarts (the page reconnects by itself), and restarting the browser then
# would only add to the outage.
watch_alive() {
    local pid=$1 dead=0 unknown=0 status
    napping=""
    trap '[[ -z $napping ]] || kill "$napping" 2>/dev/null; exit 0' TERM
    nap "$alive_grace"
    while kill -0 "$pid" 2>/dev/null; do
        status=0
        if ((has_timeout)); then
            timeout 10 bash -c "$alive" </dev/null >/dev/null 2>&1 || status=$?
        else
            bash -c "$alive" </dev/null >/dev/null 2>&1 || status=$?
        fi
        case $status in
            0)
                ((unknown == 0)) || log "--alive answers again (after $unknown answer(s) that could not tell); the page is connected"
                dead=0 unknown=0
                ;;
            1)
                dead=$((dead + 1)) unknown=0
                if ((dead >= alive_fails)); then
                    log "the page is not connected to Docent: its tab crashed or hung; restarting the browser" \
                        "(--alive said dead $dead times in a row, every ${alive_every} s)"
                    stop_process "$pid"
                    exit 0
                fi
                ;;
            *)
                ((unknown > 0)) || log "--alive cannot tell whether the page is connected (status $status;" \
                    "is Docent reachable?); leaving the browser alone until it can"
                dead=0 unknown=$((unknown + 1))
                ;;
        esac
        nap "$alive_every"
    done
}

has_timeout=0
if command -v timeout >/dev/null 2>&1; then has_timeout=1; fi
child=""
watcher=""
stopping=0
# Ends the --alive watcher of the last start, if it still runs.
end_watcher() {
    if [[ -n $watcher ]]; then
        kill -TERM "$watcher" 2>/dev/null || true
        wait "$watcher" 2>/dev/null || true
        watcher=""
    fi
}
stop() {
    stopping=1
    log "stopping"
    end_watcher
    if [[ -n $child ]] && kill -0 "$child" 2>/dev/null; then
        stop_process "$child"
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
    if [[ -n $alive ]]; then
        watch_alive "$child" &
        watcher=$!
    fi
    status=0
    wait "$child" || status=$?
    child=""
    end_watcher
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
