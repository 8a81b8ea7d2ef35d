#!/usr/bin/env python3
"""The lockstep cell across three hosts under packet loss from start-up (issue 22, decision 91).

Runs the part transfer on launch/machines/cell_3ncu.yaml across three simulated hosts
(tests/hosts/hostnet.py), with PERCENT % of the packets each host receives from the others
dropped (iptables' statistic match) from before the launchers start until HEAL seconds after
the coordinator's "starting the run" (never, with --heal-after -1). For each run it prints the
launchers' exit codes (0: the run ended as the programs say; 1: it did not, e.g. alarm 3001, the
launcher's standstill limit), the time from the start to the end, and how many times a
process logged that a cycle waited 2 s or more for an input. A run's logs are kept in the
build tree when it fails.

usage: bench/hosts_loss.py [--runs N] [--percent P] [--heal-after S] [--machine FILE]
                          [--build DIR]  (root; FILE: a cell_3ncu.yaml, e.g. on another middleware)
"""
import argparse
import os
import shutil
import subprocess
import sys
import time

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HOSTNET = os.path.join(SOURCE, "tests", "hosts", "hostnet.py")
PROGRAMS = ["--program", "CH1=launch/programs/part_transfer_ch1.nc",
            "--program", "CH2=launch/programs/part_transfer_ch2.nc"]
HOSTS = ("ncu2", "ncu3", "ncu1")  # the coordinator last, as the tests start them


def hostnet(*args, check=True):
    return subprocess.run([sys.executable, HOSTNET, *args], check=check, capture_output=True)


def one_run(k, args, mcnc, work):
    prefix = "mhl%d" % k
    hostnet("up", "--prefix", prefix, "--hosts", "ncu1,ncu2,ncu3", "--offset-ms",
            "ncu2=3,ncu3=-7", "--subnet", "10.77.137")
    try:
        hostnet("loss", "--prefix", prefix, str(args.percent))
        env = dict(os.environ, MCNC_DOMAIN="137")
        procs = {}
        for host in HOSTS:
            argv = [sys.executable, HOSTNET, "exec", "--prefix", prefix, host, "--", mcnc, "run",
                    args.machine, *PROGRAMS, "--trace",
                    work + "/trace.jsonl", "--log-level", "info", "--timeout", "600", "--host",
                    host]
            procs[host] = subprocess.Popen(argv, stdout=subprocess.DEVNULL,
                                           stderr=open(os.path.join(work, host + ".err"), "w"),
                                           env=env)
        t0 = time.time()
        while time.time() - t0 < 120:
            with open(os.path.join(work, "ncu1.err")) as f:
                if "starting the run" in f.read():
                    break
            time.sleep(0.2)
        started = time.time()
        if args.heal_after >= 0:
            time.sleep(args.heal_after)
            hostnet("heal", "--prefix", prefix)
        codes = {}
        for host, p in procs.items():
            try:
                codes[host] = p.wait(timeout=700)
            except subprocess.TimeoutExpired:
                p.kill()
                codes[host] = "timeout"
        slow = 0
        for host in HOSTS:
            with open(os.path.join(work, host + ".err")) as f:
                slow += f.read().count("still waits")
        return codes, time.time() - started, slow
    finally:
        hostnet("down", "--prefix", prefix, check=False)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--runs", type=int, default=10)
    parser.add_argument("--percent", type=float, default=10)
    parser.add_argument("--heal-after", type=float, default=8,
                        help="seconds of the run under loss (-1: all of it)")
    parser.add_argument("--machine", default="launch/machines/cell_3ncu.yaml")
    parser.add_argument("--build", default=os.path.join(SOURCE, "build"))
    args = parser.parse_args()
    mcnc = os.path.join(args.build, "bin", "mcnc")
    os.chdir(SOURCE)
    failed = 0
    for k in range(args.runs):
        work = os.path.join(args.build, "bench-hosts-loss", "run%d" % k)
        shutil.rmtree(work, ignore_errors=True)
        os.makedirs(work)
        codes, seconds, slow = one_run(k, args, mcnc, work)
        ok = all(c == 0 for c in codes.values())
        failed += 0 if ok else 1
        print("run %d: exit %s, %.1f s from the start, %d slow-wait lines%s"
              % (k, " ".join("%s=%s" % (h, codes[h]) for h in sorted(codes)), seconds, slow,
                 "" if ok else " (logs: %s)" % work), flush=True)
        if ok:
            shutil.rmtree(work, ignore_errors=True)
        time.sleep(1)
    print("%d of %d runs did not end as the programs say (%.0f %% loss%s)"
          % (failed, args.runs, args.percent,
             "" if args.heal_after < 0 else ", healed %g s into the run" % args.heal_after))


if __name__ == "__main__":
    main()
