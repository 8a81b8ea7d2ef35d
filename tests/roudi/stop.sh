#!/usr/bin/env bash
# ctest fixture "roudi" clean-up: stops the RouDi that start.sh started (none if it found one).
# Usage: stop.sh BUILD_DIR
set -uo pipefail
pidfile="$1/roudi.pid"
[ -f "$pidfile" ] || exit 0
pid="$(cat "$pidfile")"
rm -f "$pidfile"
kill -TERM "$pid" 2>/dev/null || exit 0
for _ in $(seq 1 250); do
  kill -0 "$pid" 2>/dev/null || exit 0
  sleep 0.02
done
kill -KILL "$pid" 2>/dev/null
exit 0
