#!/bin/sh
# Inside user-mode Linux (uml_run.sh): the example lathe on real kernel CAN (socketcan:vcan0),
# the xz program in lockstep, candump recording every frame as an independent witness.
#   machine_on_vcan.sh SOURCE_DIR BUILD_DIR [--drive-refuse-sdo BUS:NODE:INDEX]
# Checks (python3 below): the run ended on its points without alarm (or, with a refusal, the
# start-up failed naming the object), and the bus carried what CiA 301/402 say it must.
set -u
src=$1
build=$2
shift 2
work=$(mktemp -d /tmp/mcnc-vcan-XXXXXX)
sed 's|udp:[0-9.]*:[0-9]*|socketcan:vcan0|' "$src/launch/machines/small_lathe.yaml" > "$work/lathe.yaml"
candump -L vcan0 > "$work/candump.log" &
dump=$!
"$build/bin/mcnc" run "$work/lathe.yaml" --program "CH1=$src/launch/programs/xz_move.nc" \
  --trace "$work/trace.jsonl" "$@" > "$work/run.log" 2>&1
rc=$?
sleep 0.2
kill $dump
wait $dump 2>/dev/null
python3 - "$work" "$rc" "$#" <<'PY'
import json, sys
work, rc, refusing = sys.argv[1], int(sys.argv[2]), sys.argv[3] != "0"
frames = [line.split()[2] for line in open(work + "/candump.log") if len(line.split()) == 3]
run = open(work + "/run.log").read()
def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    return ok
good = True
if refusing:
    good &= check(rc == 1, "the run fails (exit %d)" % rc)
    good &= check("writing 0x6060:00 (modes of operation) was refused" in run,
                  "the alarm names the refused object")
    good &= check("601#2F60600008000000" in frames, "the refused write went over the bus")
    good &= check("581#8060600022000008" in frames, "the drive's abort 0x08000022 went over the bus")
    good &= check(not any(f.startswith("201#") for f in frames), "no RPDO to node 1: nothing moved it")
else:
    trace = [json.loads(l) for l in open(work + "/trace.jsonl")]
    summary = trace[-1]
    good &= check(rc == 0 and summary.get("ok") is True, "the run ends without alarm (exit %d)" % rc)
    good &= check(summary["channels"]["CH1"]["end"] == 30, "the program ended with M30")
    last = {}
    for e in trace:
        if e.get("ev") == "pos":
            last[e["axis"]] = e
    good &= check(abs(last["X1"]["act"] - 30.0) < 0.001 and abs(last["Z1"]["act"] - 10.0) < 0.001,
                  "the drives stand on X60 (r30) Z10: %s" % {k: v["act"] for k, v in last.items()})
    for node in (1, 2):
        good &= check("000#82%02X" % node in frames, "NMT reset communication of node %d" % node)
        good &= check("7%02X#00" % node in frames, "boot-up of node %d" % node)
        good &= check("6%02X#4000100000000000" % node in frames, "device type read from node %d" % node)
        good &= check("6%02X#2F60600008000000" % node in frames, "mode CSP written to node %d" % node)
        good &= check("000#01%02X" % node in frames, "NMT start of node %d" % node)
    syncs = sum(1 for f in frames if f.startswith("080#"))
    tpdos = sum(1 for f in frames if f.startswith("181#"))
    cycles = summary["cycles"]
    good &= check(syncs >= cycles, "a SYNC every cycle (%d SYNC, %d cycles)" % (syncs, cycles))
    good &= check(tpdos >= cycles - 10, "node 1 answered every SYNC (%d TPDO1)" % tpdos)
sys.exit(0 if good else 1)
PY
status=$?
[ $status -eq 0 ] || { echo "--- run log"; tail -20 "$work/run.log"; }
rm -rf "$work"
exit $status
