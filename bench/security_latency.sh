#!/usr/bin/env bash
# The setpoint latency of a secured machine (issue 25): mcnc_bench_setpoint_latency on the
# small lathe, unsecured and secured with each `mcnc certs --protection`, on each DDS
# implementation. The bench plays the launcher (RouDi, processes, run control) with the
# launcher's identity, and starts the channel's part as a process with the channel's identity.
# Usage: [MIDDLEWARES="cyclonedds fastdds"] [PROTECTIONS="off access sign encrypt"]
#        [CYCLES=10000] [DOMAIN=78] bench/security_latency.sh [BUILD_DIR]
. "$(dirname "$0")/security_bench.sh"
domain=${DOMAIN:-78}
# A private bus and domain, and a deadline that a stall does not turn into a quick stop.
sed "s|udp:[0-9.]*:[0-9]*|udp:239.255.$domain.1:$((24000 + domain))|; s/deadline_cycles: 20/deadline_cycles: 100/" \
  "$here/launch/machines/small_lathe.yaml" > "$tmp/base.yaml"
for middleware in ${MIDDLEWARES:-cyclonedds fastdds}; do
  for protection in ${PROTECTIONS:-off access sign encrypt}; do
    dir="$tmp/$middleware-$protection"
    secured_machine "$build" "$tmp/base.yaml" "$dir" "$middleware" "$protection"
    echo "$middleware $protection:"
    MCNC_DOMAIN=$domain "$build/bin/mcnc_bench_setpoint_latency" "$dir/m.yaml" \
      --cycles "${CYCLES:-10000}" 2>&1 | grep -v '^\[\|^Log level' || echo "  failed"
  done
done
