#!/bin/sh
# Inside the QEMU guest (qemu_run.sh): the example lathe on real kernel CAN (socketcan:vcan0),
# in lockstep, candump recording every frame as an independent witness.
#   machine_on_vcan.sh SOURCE_DIR BUILD_DIR SCENARIO
# SCENARIO:
#   xz           the xz program ends on its points without alarm; start-up frames on the bus
#   refused_sdo  node 1 refuses 0x6060: the start-up fails naming the object, nothing moves
#   csp_10k      over 10 000 CSP cycles with a 1.2 mm following-error limit: no alarm
#   fault_reset  over-current EMCY at SYNC 2000, operator reset at 3000, cycle start at 3100:
#                the alarm, the fault reset and enable frames, the program run again
#   heartbeat    node 2 stops its heartbeat at SYNC 1500: alarm and quick stop in time
#   frames       the spindle lathe on vcan0 (X, Z) and vcan1 (the spindle), spindle_turn.nc:
#                the frames a CANopen engineer looks for, counted against the machine file
#                (bus_witness.cpp)
# Checks in python3 below, from the trace and from candump's record of the bus.
set -u
src=$1
build=$2
scenario=$3
work=$(mktemp -d -t mcnc-vcan-XXXXXX)  # in the guest's TMPDIR, its memory
sed 's|udp:[0-9.]*:[0-9]*|socketcan:vcan0|' "$src/launch/machines/small_lathe.yaml" > "$work/lathe.yaml"
program="$src/launch/programs/xz_move.nc"
buses=vcan0
set --
case $scenario in
  xz) ;;
  refused_sdo) set -- --drive-refuse-sdo can0:1:0x6060 ;;
  csp_10k)
    program="$src/tests/integration/programs/csp_back_and_forth.nc"
    sed -i 's|^\(    in_position: .*\)$|\1\n    following_error_limit: 1.2|' "$work/lathe.yaml" ;;
  fault_reset)
    set -- --drive-fault can0:1:overcurrent@2000 --operator reset@3000 \
      --operator cycle_start:CH1@3100 ;;
  heartbeat) set -- --drive-fault can0:2:heartbeat_stop@1500 ;;
  frames)
    # can0 on vcan0, can1 on vcan1, in the machine file's order.
    awk '/uri: udp:/ { sub(/udp:[0-9.]*:[0-9]*/, "socketcan:vcan" n++) } { print }' \
      "$src/launch/machines/spindle_lathe.yaml" > "$work/lathe.yaml"
    program="$src/launch/programs/spindle_turn.nc"
    buses="vcan0 vcan1" ;;
  *) echo "unknown scenario $scenario"; exit 2 ;;
esac
# shellcheck disable=SC2086  # one argument per interface
# A receive buffer of 4 MiB, and -d: a frame candump could not take is said, not just missing.
candump -L -d -r 4194304 $buses > "$work/candump.log" &
dump=$!
# The record must hold the drives' power-on boot-ups: wait until candump's receivers are in
# the kernel's list of every bus before the machine starts.
listening() {
  for bus in $buses; do
    grep -Eq "^ +$bus +000 +00000000 .* raw\$" /proc/net/can/rcvlist_all || return 1
  done
}
tries=0
until listening; do
  tries=$((tries + 1))
  if [ $tries -gt 100 ]; then
    echo "FAIL candump is not listening on $buses after 5 s"
    kill $dump
    exit 1
  fi
  sleep 0.05
done
# The run's log goes to standard output too, which qemu_run.sh shows as it comes: when its
# time limit cuts the run short, how far it got.
{
  "$build/bin/mcnc" run "$work/lathe.yaml" --program "CH1=$program" \
    --trace "$work/trace.jsonl" "$@" 2>&1
  echo $? > "$work/rc"
} | tee "$work/run.log"
rc=$(cat "$work/rc" 2>/dev/null || echo 1)  # no file: the run's shell was killed
sleep 0.2
kill $dump
wait $dump 2>/dev/null
if grep -q DROPCOUNT "$work/candump.log"; then
  echo "FAIL candump lost frames, so its record is no witness: $(grep DROPCOUNT "$work/candump.log" | tail -1)"
  rm -rf "$work"
  exit 1
fi
if [ "$scenario" = frames ]; then
  status=1
  if [ "$rc" -eq 0 ]; then
    echo "ok   the run ends without alarm"
    "$build/bin/mcnc_bus_witness" "$work/lathe.yaml" "$work/candump.log" "$work/trace.jsonl"
    status=$?
    # The witness can fail: the same record with node 2's 500th TPDO1 lost and a frame no
    # node of the machine file sends must fail exactly those two checks.
    awk '/ vcan0 182#/ && ++k == 500 { next } { print } END { print "(0.0) vcan0 123#00" }' \
      "$work/candump.log" > "$work/tampered.log"
    "$build/bin/mcnc_bus_witness" "$work/lathe.yaml" "$work/tampered.log" "$work/trace.jsonl" \
      > "$work/tampered.out"
    tampered=$?
    fails=$(grep '^FAIL' "$work/tampered.out" | sed 's/ ([^()]*)$//')
    if [ $tampered -eq 1 ] && [ "$(echo "$fails" | wc -l)" -eq 2 ] &&
       echo "$fails" | grep -q '^FAIL can0 (vcan0): .* frames, none outside what the machine file accounts for: 0x123 x1$' &&
       echo "$fails" | grep -q '^FAIL can0 (vcan0) node 2 (Z1): 0x182 once in every SYNC interval$'; then
      echo "ok   a record with a lost TPDO1 and a stranger fails the witness on exactly those"
    else
      echo "FAIL a record with a lost TPDO1 and a stranger fails the witness on exactly those:"
      cat "$work/tampered.out"
      status=1
    fi
  else
    echo "FAIL the run ends without alarm (exit $rc)"
  fi
  rm -rf "$work"
  exit $status
fi
python3 - "$work" "$rc" "$scenario" <<'PY'
import json, sys
work, rc, scenario = sys.argv[1], int(sys.argv[2]), sys.argv[3]
frames = [line.split()[2] for line in open(work + "/candump.log") if len(line.split()) == 3]
run = open(work + "/run.log").read()
def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    return ok
def trace():
    return [json.loads(l) for l in open(work + "/trace.jsonl")]
def last_pos(t):
    last = {}
    for e in t:
        if e.get("ev") == "pos":  # the axis nodes' samples and the channel's block ends
            last[e["axis"]] = e
    return last
def controlwords(node):
    # Controlwords of the RPDOs to `node`, in bus order, repeats folded.
    out = []
    for f in frames:
        if f.startswith("2%02X#" % node):
            cw = int(f[4:6], 16) | int(f[6:8], 16) << 8
            if not out or out[-1] != cw:
                out.append(cw)
    return out
good = True
if scenario == "refused_sdo":
    good &= check(rc == 1, "the run fails (exit %d)" % rc)
    good &= check("writing 0x6060:00 (modes of operation) was refused" in run,
                  "the alarm names the refused object")
    good &= check("601#2F60600008000000" in frames, "the refused write went over the bus")
    good &= check("581#8060600022000008" in frames, "the drive's abort 0x08000022 went over the bus")
    good &= check(not any(f.startswith("201#") for f in frames), "no RPDO to node 1: nothing moved it")
elif scenario in ("xz", "csp_10k"):
    t = trace()
    summary = t[-1]
    good &= check(rc == 0 and summary.get("ok") is True, "the run ends without alarm (exit %d)" % rc)
    good &= check(summary["channels"]["CH1"]["end"] == 30, "the program ended with M30")
    cycles = summary["cycles"]
    if scenario == "xz":
        last = last_pos(t)
        good &= check(abs(last["X1"]["act"] - 30.0) < 0.001 and abs(last["Z1"]["act"] - 10.0) < 0.001,
                      "the drives stand on X60 (r30) Z10: %s" % {k: v["act"] for k, v in last.items()})
        for node in (1, 2):
            good &= check("000#82%02X" % node in frames, "NMT reset communication of node %d" % node)
            good &= check("7%02X#00" % node in frames, "boot-up of node %d" % node)
            good &= check("6%02X#4000100000000000" % node in frames, "device type read from node %d" % node)
            good &= check("6%02X#2F60600008000000" % node in frames, "mode CSP written to node %d" % node)
            good &= check("000#01%02X" % node in frames, "NMT start of node %d" % node)
    else:
        worst = max(abs(e["cmd"] - e["act"]) for e in t if e.get("ev") == "pos" and e["src"] in ("X1", "Z1"))
        good &= check(cycles >= 10000, "over 10 000 cycles (%d)" % cycles)
        good &= check(0.1 < worst < 1.2, "following error within the 1.2 mm bound, at speed (%.3f mm)" % worst)
    syncs = sum(1 for f in frames if f.startswith("080#"))
    tpdos = sum(1 for f in frames if f.startswith("181#"))
    good &= check(syncs >= cycles, "a SYNC every cycle (%d SYNC, %d cycles)" % (syncs, cycles))
    good &= check(tpdos >= cycles - 10, "node 1 answered every SYNC (%d TPDO1)" % tpdos)
elif scenario == "fault_reset":
    t = trace()
    alarms = [e for e in t if e.get("ev") == "alarm"]
    good &= check(rc == 1, "the run keeps its alarm in the result (exit %d)" % rc)
    good &= check([a["number"] for a in alarms] == [2003, 1201] and alarms[0]["text"] ==
                  "drive fault: EMCY 0x2310 continuous over-current",
                  "alarm 2003 with the EMCY in words, then the channel's: %s" % [(a["number"], a["text"]) for a in alarms])
    good &= check("081#1023030000000000" in frames, "the drive's EMCY 0x2310 went over the bus")
    cws = controlwords(1)
    tail = cws[cws.index(0x0080):] if 0x0080 in cws else []
    good &= check(tail[:4] == [0x0080, 0x0006, 0x0007, 0x000F],
                  "after the EMCY: fault reset, shutdown, switch on, enable operation (%s)" %
                  ["0x%04X" % c for c in tail[:4]])
    back = [e for e in t if e.get("ev") == "drive" and e["src"] == "X1" and e["cycle"] >= 3000]
    good &= check(back and back[-1]["state"] == "operation_enabled" and back[-1]["cycle"] <= 3010,
                  "X1's drive is back in operation by cycle 3010")
    ends = [e for e in t if e.get("ev") == "end"]
    good &= check(len(ends) == 1 and ends[0]["cycle"] > 3100, "the program ran again to its end")
    last = last_pos(t)
    good &= check(abs(last["X1"]["act"] - 30.0) < 0.001 and abs(last["Z1"]["act"] - 10.0) < 0.001,
                  "the drives stand on X60 (r30) Z10")
elif scenario == "heartbeat":
    t = trace()
    alarms = [e for e in t if e.get("ev") == "alarm" and e["src"] == "Z1"]
    good &= check(rc == 1, "the run fails (exit %d)" % rc)
    good &= check(len(alarms) == 1 and alarms[0]["number"] == 2006, "alarm 2006 from Z1")
    # Heartbeats every 100 ms of SYNC time: the last at SYNC 1400, the consumer time 150 cycles,
    # SYNC and cycle numbers a few start-up cycles apart.
    good &= check(alarms and 1500 <= alarms[0]["cycle"] <= 1400 + 151 + 20,
                  "within the consumer time of the last heartbeat (cycle %s)" % (alarms[0]["cycle"] if alarms else None))
    hb = [i for i, f in enumerate(frames) if f == "702#05"]
    good &= check(len(hb) >= 10, "node 2's heartbeats were on the bus (%d)" % len(hb))
    after = frames[hb[-1] + 1:] if hb else []
    good &= check(sum(1 for f in after if f.startswith("080#")) >= 150,
                  "then silence for at least the consumer time of SYNCs")
    good &= check(0x0002 in controlwords(2), "quick stop (controlword 0x0002) sent to node 2")
sys.exit(0 if good else 1)
PY
status=$?
rm -rf "$work"
exit $status
