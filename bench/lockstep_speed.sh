#!/usr/bin/env bash
# Lockstep speed: runs programs with `mcnc run` in the lockstep clock RUNS times and prints
# cycles, wall time, cycles per second and the ratio to real time.
# Usage: bench/lockstep_speed.sh [BUILD_DIR] [RUNS] [MACHINE CH=PROGRAM...]
# (default: launch/machines/small_lathe.yaml CH1=launch/programs/xz_move.nc; paths relative to
# the source tree)
set -euo pipefail
build=${1:-build}
runs=${2:-5}
here=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# A private bus and domain, so the bench does not meet anything else running.
machine=${3:-launch/machines/small_lathe.yaml}
shift $(( $# < 3 ? $# : 3 ))
programs=()
for p in "${@:-CH1=launch/programs/xz_move.nc}"; do
  programs+=(--program "${p%%=*}=$here/${p#*=}")
done
# Each bus on its own private group.
awk '{ out = ""; while (match($0, /udp:[0-9.]+:[0-9]+/)) { n++; out = out substr($0, 1, RSTART - 1) "udp:239.255.77." n ":" (24076 + n); $0 = substr($0, RSTART + RLENGTH) } print out $0 }' \
  "$here/$machine" > "$tmp/m.yaml"
# A program directory stays the one beside the original machine file.
sed -i "s|program_dir: *\([^/].*\)|program_dir: $(dirname "$here/$machine")/\1|" "$tmp/m.yaml"
cycle_us=$(sed -n 's/^ *cycle_us: *\([0-9]*\).*/\1/p' "$tmp/m.yaml")
for i in $(seq "$runs"); do
  start=$(date +%s.%N)
  out=$(MCNC_DOMAIN=77 "$build/bin/mcnc" run "$tmp/m.yaml" "${programs[@]}" --log-level warn)
  end=$(date +%s.%N)
  cycles=$(echo "$out" | sed -n 's/^ok after \([0-9]*\) cycles$/\1/p')
  [ -n "$cycles" ] || { echo "run $i failed:"; echo "$out"; exit 1; }
  awk -v c="$cycles" -v s="$start" -v e="$end" -v us="$cycle_us" -v i="$i" 'BEGIN {
    wall = e - s; printf "run %d: %d cycles in %.2f s wall (start-up and stop included): %.0f cycles/s, %.2f x real time\n", i, c, wall, c / wall, (c * us / 1e6) / wall }'
done
