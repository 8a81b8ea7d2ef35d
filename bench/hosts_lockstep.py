#!/usr/bin/env python3
"""Lockstep speed of a machine across hosts against the same machine on one host (issue 22).

Runs the part transfer on launch/machines/cell_3ncu.yaml: first with every process on this
host (`mcnc run` without --host), then across three simulated hosts (tests/hosts/hostnet.py:
network, mount and time namespaces; clocks at +0, +3 and -7 ms), a launcher on each. Each run
is timed from the coordinator's "starting the run" to its end, from its log's timestamps, so
that the start-up (discovery, drive bring-up) and the stop are left out. Prints the times and the ratio
(one host / three hosts: 1.0 means the network costs nothing).

usage: bench/hosts_lockstep.py [--runs N] [--build DIR]    (root: it makes namespaces)
"""
import argparse
import datetime
import os
import re
import shutil
import subprocess
import sys
import time

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HOSTNET = os.path.join(SOURCE, "tests", "hosts", "hostnet.py")
PROGRAMS = ["--program", "CH1=launch/programs/part_transfer_ch1.nc",
            "--program", "CH2=launch/programs/part_transfer_ch2.nc"]
STAMP = re.compile(r"^\[(\d\d):(\d\d):(\d\d)\.(\d{3})\]")


def run_seconds(log):
    """Seconds from "starting the run" to the next timestamped line of the coordinator's log,
    the first process's stop at the run's end (the progress lines between have no stamp)."""
    start = end = None
    for line in log.splitlines():
        m = STAMP.match(line)
        if not m:
            continue
        t = (int(m[1]) * 3600 + int(m[2]) * 60 + int(m[3])) + int(m[4]) / 1000
        if "starting the run" in line:
            start = t
        elif start is not None and "clock offset" not in line:  # the hosts' clocks, at the start
            end = t
            break
    if start is None or end is None:
        raise SystemExit("no run in the log:\n" + log[-2000:])
    return end - start


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--build", default=os.path.join(SOURCE, "build"))
    args = parser.parse_args()
    mcnc = os.path.join(args.build, "bin", "mcnc")
    work = os.path.join(args.build, "bench-hosts")
    os.chdir(SOURCE)
    one, three = [], []
    for k in range(args.runs):
        shutil.rmtree(work, ignore_errors=True)
        os.makedirs(work)
        env = dict(os.environ, MCNC_DOMAIN="201")
        r = subprocess.run([mcnc, "run", "launch/machines/cell_3ncu.yaml", *PROGRAMS,
                            "--trace", work + "/one.jsonl", "--log-level", "info"],
                           capture_output=True, text=True, env=env)
        if r.returncode != 0:
            raise SystemExit("one-host run failed:\n" + r.stdout + r.stderr)
        one.append(run_seconds(r.stderr))

        prefix = "mhb%d" % k
        subprocess.run([sys.executable, HOSTNET, "up", "--prefix", prefix, "--hosts",
                        "ncu1,ncu2,ncu3", "--offset-ms", "ncu2=3,ncu3=-7", "--subnet",
                        "10.77.201"], check=True, capture_output=True)
        try:
            def launcher(host):
                return [sys.executable, HOSTNET, "exec", "--prefix", prefix, host, "--", mcnc,
                        "run", "launch/machines/cell_3ncu.yaml", *PROGRAMS, "--trace",
                        work + "/three.jsonl", "--log-level", "info", "--host", host]
            followers = [subprocess.Popen(launcher(h), stdout=subprocess.DEVNULL,
                                          stderr=subprocess.DEVNULL, env=env)
                         for h in ("ncu2", "ncu3")]
            r = subprocess.run(launcher("ncu1"), capture_output=True, text=True, env=env)
            for f in followers:
                f.wait(timeout=120)
            if r.returncode != 0:
                raise SystemExit("three-host run failed:\n" + r.stdout + r.stderr)
            three.append(run_seconds(r.stderr))
        finally:
            subprocess.run([sys.executable, HOSTNET, "down", "--prefix", prefix])
        time.sleep(1)
    print("date %s, %d runs of the part transfer (7 256 cycles of 2 ms, 14.5 s of machine time)"
          % (datetime.date.today(), args.runs))
    print("one host:    " + "  ".join("%.2f s" % t for t in one))
    print("three hosts: " + "  ".join("%.2f s" % t for t in three))
    best_one, best_three = min(one), min(three)
    print("best: one host %.2f s (%.2f x real time), three hosts %.2f s (%.2f x real time); "
          "three hosts run at %.2f x the one-host speed"
          % (best_one, 14.512 / best_one, best_three, 14.512 / best_three, best_one / best_three))


if __name__ == "__main__":
    main()
