#!/usr/bin/env bash
# The price of DDS Security (issue 25): runs one machine's programs in the lockstep clock
# unsecured and secured with each `mcnc certs --protection`, on each DDS implementation, and
# prints per run the machine cycles, wall time and CPU (user + system of every process of the
# machine, start-up included) per machine cycle.
# Usage: [MIDDLEWARES="cyclonedds fastdds"] [PROTECTIONS="off access sign encrypt"]
#        bench/security_price.sh [BUILD_DIR] [MACHINE CH=PROGRAM...]
# (default: the twin turret's CT-G1141-01 part transfer; paths relative to the source tree)
. "$(dirname "$0")/security_bench.sh"
machine=${2:-launch/machines/twin_turret.yaml}
shift $(( $# < 2 ? $# : 2 ))
programs=()
for p in "${@:-CH1=tests/integration/programs/g1141/ch1.nc CH2=tests/integration/programs/g1141/ch2.nc}"; do
  for q in $p; do
    programs+=(--program "${q%%=*}=$here/${q#*=}")
  done
done
# A private bus and domain, so the bench does not meet anything else running.
awk '{ out = ""; while (match($0, /udp:[0-9.]+:[0-9]+/)) { n++; out = out substr($0, 1, RSTART - 1) "udp:239.255.76." n ":" (24176 + n); $0 = substr($0, RSTART + RLENGTH) } print out $0 }' \
  "$here/$machine" > "$tmp/base.yaml"
sed -i "s|program_dir: *\([^/].*\)|program_dir: $(dirname "$here/$machine")/\1|" "$tmp/base.yaml"
TIMEFORMAT='%R %U %S'
printf '%-10s %-11s %7s %8s %14s\n' middleware protection cycles wall "CPU per cycle"
for middleware in ${MIDDLEWARES:-cyclonedds fastdds}; do
  for protection in ${PROTECTIONS:-off access sign encrypt}; do
    dir="$tmp/$middleware-$protection"
    secured_machine "$build" "$tmp/base.yaml" "$dir" "$middleware" "$protection"
    times=$( { time MCNC_DOMAIN=76 "$build/bin/mcnc" run "$dir/m.yaml" "${programs[@]}" \
                 --log-level warn > "$dir/out" 2>&1; } 2>&1 ) ||
      { echo "$middleware $protection failed:"; grep -v '^\[' "$dir/out" | tail -5; continue; }
    cycles=$(sed -n 's/^ok after \([0-9]*\) cycles$/\1/p' "$dir/out")
    read -r wall user sys <<< "$times"
    awk -v m="$middleware" -v p="$protection" -v c="$cycles" -v w="$wall" -v u="$user" -v s="$sys" \
      'BEGIN { printf "%-10s %-11s %7d %7.2fs %11.0f us\n", m, p, c, w, (u + s) * 1e6 / c }'
  done
done
