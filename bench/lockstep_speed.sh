#!/usr/bin/env bash
# Lockstep speed of the test machine: runs a program with `mcnc run` in the lockstep clock
# RUNS times and prints cycles, wall time, cycles per second and the ratio to real time.
# Usage: bench/lockstep_speed.sh [BUILD_DIR] [RUNS]
set -euo pipefail
build=${1:-build}
runs=${2:-5}
here=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# A private bus and domain, so the bench does not meet anything else running.
sed 's|udp:[0-9.]*:[0-9]*|udp:239.255.77.1:24077|' "$here/launch/machines/small_lathe.yaml" > "$tmp/m.yaml"
cycle_us=$(sed -n 's/^ *cycle_us: *\([0-9]*\).*/\1/p' "$tmp/m.yaml")
for i in $(seq "$runs"); do
  start=$(date +%s.%N)
  out=$(MCNC_DOMAIN=77 "$build/bin/mcnc" run "$tmp/m.yaml" --program "CH1=$here/launch/programs/xz_move.nc" --log-level warn)
  end=$(date +%s.%N)
  cycles=$(echo "$out" | sed -n 's/^ok after \([0-9]*\) cycles$/\1/p')
  [ -n "$cycles" ] || { echo "run $i failed:"; echo "$out"; exit 1; }
  awk -v c="$cycles" -v s="$start" -v e="$end" -v us="$cycle_us" -v i="$i" 'BEGIN {
    wall = e - s; printf "run %d: %d cycles in %.2f s wall (start-up and stop included): %.0f cycles/s, %.2f x real time\n", i, c, wall, c / wall, (c * us / 1e6) / wall }'
done
