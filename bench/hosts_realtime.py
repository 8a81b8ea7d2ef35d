#!/usr/bin/env python3
"""A machine across hosts in the realtime clock (issue 22): the cycle alignment between hosts
whose clocks differ, and the G04.1 release across three hosts.

Makes three simulated hosts (tests/hosts/hostnet.py: network, mount and time namespaces; their
CLOCK_MONOTONIC at +0, +3 and -7 ms) and runs launch/machines/cell_3ncu.yaml on them, a
launcher on each, realtime, Cyclone DDS:

1. The part transfer with a `tick` every cycle from every axis node. A tick has the cycle's due
   time on its host's clock and the wake-up's lateness; taken back to ncu1's clock with the
   true offsets (the namespaces'), each cycle's due times and wake-ups on the three hosts give
   the alignment: the largest difference between two hosts, per cycle. Also each host's
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
        followers = [subprocess.Popen(launcher(h), stdout=subprocess.DEVNULL,
                                      stderr=subprocess.DEVNULL, env=env)
                     for h in ("ncu2", "ncu3")]
        r = subprocess.run(launcher("ncu1"), capture_output=True, text=True, env=env)
        for f in followers:
            f.wait(timeout=120)
    finally:
        subprocess.run([sys.executable, HOSTNET, "down", "--prefix", prefix])
    with open(trace) as f:
        events = [json.loads(line) for line in f]
    return r, events


def pct(values, q):
    values = sorted(values)
    return values[min(len(values) - 1, int(q * len(values)))]


def alignment(events):
    due, woke = {}, {}  # cycle -> host -> ns on ncu1's clock
    for e in events:
        if e["ev"] != "tick":
            continue
        host = HOST_OF[e["axis"]]
        t = e["due_ns"] - OFFSET_NS[host]
        due.setdefault(e["cycle"], {})[host] = t
        woke.setdefault(e["cycle"], {}).setdefault(host, []).append(t + e["late_ns"])
    spread_due = [max(h.values()) - min(h.values()) for h in due.values() if len(h) == 3]
    # A host's cycle starts when its first axis node wakes for it.
    spread_woke = []
    for hosts in woke.values():
        if len(hosts) == 3:
            starts = [min(ts) for ts in hosts.values()]
            spread_woke.append(max(starts) - min(starts))
    return spread_due, spread_woke


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
    for e in events:
        if e["ev"] == "clock":
            print("  %s: estimated offset %+.1f us (+-%.1f us, %d exchanges), true %+.1f us, "
                  "error %+.1f us" % (e["host"], e["offset_ns"] / 1e3, e["error_ns"] / 1e3,
                                      e["samples"], OFFSET_NS[e["host"]] / 1e3,
                                      (e["offset_ns"] - OFFSET_NS[e["host"]]) / 1e3))
    spread_due, spread_woke = alignment(events)
    for name, spread in (("due times", spread_due), ("wake-ups", spread_woke)):
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
        print(r.stdout[-1500:])


if __name__ == "__main__":
    main()
