#!/usr/bin/env python3
"""A machine across hosts in the realtime clock (issue 22): the cycle alignment between hosts
whose clocks differ, and the G04.1 release across three hosts.

Makes three simulated hosts (tests/hosts/hostnet.py: network, mount and time namespaces; their
CLOCK_MONOTONIC at +0, +3 and -7 ms) and runs launch/machines/cell_3ncu.yaml on them, a
launcher on each, realtime, Cyclone DDS:

1. The part transfer with a `tick` every cycle from every axis node. A tick has the cycle's due
   time on its host's clock and the wake-up's lateness, a SYNC producer's also its latest
   SYNC's due time and lateness; taken back to ncu1's clock with the true offsets (the
   namespaces'), each cycle's due times, wake-ups and SYNCs on the three hosts (one bus each)
   give the alignment: the largest difference between two hosts, per cycle. Also each host's
   estimated offset against its true one.
2. The three channels (CH1 on ncu1, CH2 on ncu2, CH3 on ncu3) meet at `G04.1 P1` ROUNDS times,
   Q123 after dwells that differ by channel and round (bench/barrier_release.py's program): the
   release latency is, per round, the cycle the last channel was released minus the cycle the
   last one arrived.

usage: bench/hosts_realtime.py [--build DIR] [--rounds R]    (root: it makes namespaces)
"""
import argparse
import datetime
import json
import os
import shutil
import statistics
import subprocess
import sys

from barrier_release import program as barrier_program

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HOSTNET = os.path.join(SOURCE, "tests", "hosts", "hostnet.py")
OFFSET_NS = {"ncu1": 0, "ncu2": 3_000_000, "ncu3": -7_000_000}
HOST_OF = {"X1": "ncu1", "Z1": "ncu1", "A1": "ncu1", "S1": "ncu1", "X2": "ncu2", "Z2": "ncu2",
           "S2": "ncu2", "Z3": "ncu2", "X3": "ncu3"}


def run_on_hosts(mcnc, work, programs, extra, prefix):
    """Runs the cell on three simulated hosts; returns the coordinator's exit code and trace."""
    env = dict(os.environ, MCNC_DOMAIN="202")
    subprocess.run([sys.executable, HOSTNET, "up", "--prefix", prefix, "--hosts",
                    "ncu1,ncu2,ncu3", "--offset-ms", "ncu2=3,ncu3=-7", "--subnet", "10.77.202"],
                   check=True, capture_output=True)
    trace = os.path.join(work, prefix + ".jsonl")
    try:
        def launcher(host):
            argv = [sys.executable, HOSTNET, "exec", "--prefix", prefix, host, "--", mcnc, "run",
                    "launch/machines/cell_3ncu.yaml", "--clock", "realtime", "--trace", trace,
                    "--timeout", "300", "--host", host, *extra]
            for ch, path in programs.items():
                argv += ["--program", "%s=%s" % (ch, path)]
            return argv
        logs = [open(os.path.join(work, "%s-%s.log" % (prefix, h)), "w") for h in ("ncu2", "ncu3")]
        followers = [subprocess.Popen(launcher(h), stdout=log, stderr=subprocess.STDOUT, env=env)
                     for h, log in zip(("ncu2", "ncu3"), logs)]
        r = subprocess.run(launcher("ncu1"), capture_output=True, text=True, env=env)
        with open(os.path.join(work, prefix + "-ncu1.log"), "w") as log:
            log.write(r.stdout + r.stderr)
        for f, log in zip(followers, logs):
            f.wait(timeout=120)
            log.close()
    finally:
        subprocess.run([sys.executable, HOSTNET, "down", "--prefix", prefix])
    with open(trace) as f:
        events = [json.loads(line) for line in f]
    return r, events


def pct(values, q):
    values = sorted(values)
    return values[min(len(values) - 1, int(q * len(values)))]


def spreads(by_cycle):
    """Per cycle seen on all three hosts: the largest difference between two hosts."""
    return [max(h.values()) - min(h.values()) for h in by_cycle.values() if len(h) == 3]


def alignment(events):
    """The alignment between hosts, each list a spread per cycle: the cycles' due times, the
    first wake-up of a host's axis nodes, the SYNCs' due times and when the SYNCs went out."""
    due, woke, sync_due, sync_sent = {}, {}, {}, {}  # cycle -> host -> ns on ncu1's clock
    for e in events:
        if e["ev"] != "tick":
            continue
        host = HOST_OF[e["axis"]]
        t = e["due_ns"] - OFFSET_NS[host]
        due.setdefault(e["cycle"], {})[host] = t
        # A host's cycle starts when its first axis node wakes for it.
        first = woke.setdefault(e["cycle"], {})
        first[host] = min(first.get(host, t + e["late_ns"]), t + e["late_ns"])
        if "sync_cycle" in e:  # the host's bus's SYNC producer
            s = e["sync_due_ns"] - OFFSET_NS[host]
            sync_due.setdefault(e["sync_cycle"], {})[host] = s
            sync_sent.setdefault(e["sync_cycle"], {})[host] = s + e["sync_late_ns"]
    return spreads(due), spreads(woke), spreads(sync_due), spreads(sync_sent)


def print_alarms(events):
    """The first alarms of a run that did not end well: where its figures stop, and why."""
    for e in [e for e in events if e["ev"] == "alarm"][:4]:
        print("  alarm %s at cycle %s from %s: %s"
              % (e.get("number"), e.get("cycle"), e.get("src"), e.get("text", "")))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(SOURCE, "build"))
    parser.add_argument("--rounds", type=int, default=200)
    args = parser.parse_args()
    mcnc = os.path.join(args.build, "bin", "mcnc")
    work = os.path.join(args.build, "bench-hosts-realtime")
    os.chdir(SOURCE)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    print("date %s" % datetime.date.today())

    r, events = run_on_hosts(mcnc, work, {"CH1": "launch/programs/part_transfer_ch1.nc",
                                          "CH2": "launch/programs/part_transfer_ch2.nc"},
                             ["--trace-pos-every", "1"], "mhr1")
    print("part transfer: exit %d" % r.returncode)
    if r.returncode != 0:
        print_alarms(events)
    for e in events:
        if e["ev"] == "clock":
            print("  %s: estimated offset %+.1f us (+-%.1f us, %d exchanges), true %+.1f us, "
                  "error %+.1f us" % (e["host"], e["offset_ns"] / 1e3, e["error_ns"] / 1e3,
                                      e["samples"], OFFSET_NS[e["host"]] / 1e3,
                                      (e["offset_ns"] - OFFSET_NS[e["host"]]) / 1e3))
    spread_due, spread_woke, spread_sync_due, spread_sync = alignment(events)
    for name, spread in (("due times", spread_due), ("wake-ups", spread_woke),
                         ("SYNC due times", spread_sync_due), ("SYNCs sent", spread_sync)):
        if spread:
            print("  cycle start alignment between hosts, %s: %d cycles, median %.0f us, "
                  "p99 %.0f us, max %.0f us" % (name, len(spread), statistics.median(spread) / 1e3,
                                                pct(spread, 0.99) / 1e3, max(spread) / 1e3))
    late = [e["late_ns"] for e in events if e["ev"] == "tick"]
    if late:
        print("  wake-up lateness of the axis nodes: median %.0f us, p99 %.0f us, max %.0f us"
              % (statistics.median(late) / 1e3, pct(late, 0.99) / 1e3, max(late) / 1e3))

    prog = os.path.join(work, "barrier.nc")
    with open(prog, "w") as f:
        # The participants named (Q123): "every channel in automatic operation" (P alone) is
        # each channel's own view of the others, which differs between hosts at the start.
        f.write(barrier_program(args.rounds, 0.002).replace("G04.1 P1", "G04.1 P1 Q123"))
    r, events = run_on_hosts(mcnc, work, {"CH1": prog, "CH2": prog, "CH3": prog}, [], "mhr2")
    arrivals, releases = {}, {}
    for e in events:
        if e["ev"] == "sync_arrive":
            arrivals[e["gen"]] = max(arrivals.get(e["gen"], 0), e["cycle"])
        elif e["ev"] == "sync_release":
            releases[e["gen"]] = max(releases.get(e["gen"], 0), e["cycle"])
    lat = [releases[g] - arrivals[g] for g in sorted(arrivals) if g in releases]
    print("G04.1 across three hosts: exit %d, %d rounds" % (r.returncode, len(lat)))
    if lat:
        print("  last arrival to all released: median %.0f cycles, p99 %d cycles, max %d cycles"
              % (statistics.median(lat), pct(lat, 0.99), max(lat)))
    if r.returncode != 0:
        print_alarms(events)
        print(r.stdout[-1500:])


if __name__ == "__main__":
    main()
