#!/usr/bin/env bash
# ctest fixture "roudi": the host's iceoryx RouDi for the tests that run processes on Cyclone
# DDS, started once for the whole run. mcnc-launch uses a RouDi that answers and leaves it
# running, so the machines of tests in parallel share this one, as machines on one host do.
# Uses one that already answers (and then leaves it to its owner).
# Usage: start.sh BUILD_DIR
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
pidfile="$1/roudi.pid"
answers() {
  python3 -c 'import socket,sys
s = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
try:
    s.connect("/tmp/roudi")
except OSError:
    sys.exit(1)'
}
rm -f "$pidfile"
if answers; then
  echo "roudi fixture: a RouDi already answers; using it"
  exit 0
fi
command -v iox-roudi >/dev/null || { echo "roudi fixture: iox-roudi is not installed (scripts/install-deps)" >&2; exit 1; }
# Above everything else, as mcnc-launch starts one (launch/host_roudi.hpp: under load RouDi
# fell behind and removed live processes); as an ordinary process where that is not permitted.
fifo=()
if chrt -f 42 true 2>/dev/null; then fifo=(chrt -f 42); fi
setsid "${fifo[@]}" iox-roudi -c "$here/roudi_config.toml" -l warning -k 1 >"$1/roudi.log" 2>&1 </dev/null &
echo $! >"$pidfile"
for _ in $(seq 1 500); do
  if answers; then
    echo "roudi fixture: started RouDi (pid $(cat "$pidfile"))"
    exit 0
  fi
  sleep 0.02
done
echo "roudi fixture: RouDi did not answer within 10 s:" >&2
cat "$1/roudi.log" >&2
exit 1
