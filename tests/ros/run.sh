#!/usr/bin/env bash
# Runs a command in the ROS 2 environment of tests/ros/.venv (tests/ros/env.sh), replacing
# this shell, so that the caller's process id is the command's own (a test kills it by id).
set -euo pipefail
. "$(dirname "$0")/env.sh"
exec "$@"
