#!/usr/bin/env python3
"""G04.1 barrier release latency in the realtime clock: N one-axis channels meet at `G04.1 P1`
ROUNDS times, each arriving after a dwell that varies by channel and round, and the trace says
for every round the cycle of the last arrival and the cycle the last channel was released. The
latency is their difference, in cycles and in milliseconds; by design it is one cycle (a
channel decides from the arrivals stamped before its cycle).

Usage: bench/barrier_release.py [--build DIR] [--rounds R] [--cycle-us US] N [N ...]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

from bench_machine import machine_yaml

HERE = os.path.dirname(os.path.abspath(__file__))


def program(rounds, cycle_s):
    # The dwell before each mark: 0-4 cycles, different per channel and round.
    return (
        "#1=0\n"
        f"WHILE[#1LT{rounds}]DO1\n"
        f"G04 X[[[#1*7+CHN*3] MOD 5]*{cycle_s}]\n"
        "G04.1 P1\n"
        "#1=#1+1\n"
        "END1\n"
        "M30\n"
    )


def run(build, channels, rounds, cycle_us, domain):
    with tempfile.TemporaryDirectory() as tmp:
        machine = os.path.join(tmp, "m.yaml")
        with open(machine, "w") as f:
            f.write(machine_yaml(f"barrier_bench_{channels}", channels, 1, cycle_us, domain))
        prog = os.path.join(tmp, "p.nc")
        with open(prog, "w") as f:
            f.write(program(rounds, cycle_us / 1e6))
        trace = os.path.join(tmp, "t.jsonl")
        argv = [os.path.join(build, "bin", "mcnc"), "run", machine, "--clock", "realtime",
                "--trace", trace, "--log-level", "warn", "--timeout", "300"]
        for c in range(1, channels + 1):
            argv += ["--program", f"CH{c}={prog}"]
        env = dict(os.environ, MCNC_DOMAIN=str(domain))
        r = subprocess.run(argv, env=env, capture_output=True, text=True)
        if r.returncode != 0:
            print(r.stdout[-2000:], r.stderr[-2000:], file=sys.stderr)
            return None
        arrivals, releases = {}, {}
        with open(trace) as f:
            for line in f:
                e = json.loads(line)
                if e["ev"] == "sync_arrive":
                    arrivals[e["gen"]] = max(arrivals.get(e["gen"], 0), e["cycle"])
                elif e["ev"] == "sync_release":
                    releases[e["gen"]] = max(releases.get(e["gen"], 0), e["cycle"])
        return [releases[g] - arrivals[g] for g in sorted(arrivals) if g in releases]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(HERE, "..", "build"))
    ap.add_argument("--rounds", type=int, default=200)
    ap.add_argument("--cycle-us", type=int, default=4000)
    ap.add_argument("channels", type=int, nargs="+")
    args = ap.parse_args()
    print("| channels | rounds | median | p99 | max |")
    print("|---|---|---|---|---|")
    for i, n in enumerate(args.channels):
        lat = run(args.build, n, args.rounds, args.cycle_us, 90 + i)
        if lat is None:
            print(f"| {n} | the run failed | | | |", flush=True)
            continue
        lat.sort()
        p99 = lat[min(len(lat) - 1, int(0.99 * len(lat)))]
        ms = args.cycle_us / 1000.0
        print(f"| {n} | {len(lat)} | {statistics.median(lat):.0f} cycle ({statistics.median(lat) * ms:.0f} ms)"
              f" | {p99} cycles ({p99 * ms:.0f} ms) | {lat[-1]} cycles ({lat[-1] * ms:.0f} ms) |",
              flush=True)


if __name__ == "__main__":
    main()
