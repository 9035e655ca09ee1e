#!/bin/bash
# launch-prefix for a node that needs a file another node writes during the test: waits until
# FILE is newer than this script's start (a file left by an earlier run does not count), then runs
# the node. Usage: run_when_file_renewed.sh FILE COMMAND [ARGS...]
file="$1"
shift
marker="$(mktemp)"
trap 'rm -f "$marker"' EXIT
until [ "$file" -nt "$marker" ]; do sleep 0.2; done
rm -f "$marker"
exec "$@"
