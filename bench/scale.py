#!/usr/bin/env python3
"""How the machine scales with its channels: N channels of two axes (X, Z) each, four axes per
CAN bus, a 2 ms cycle (--axes 4 adds Y and a linear A to each channel, --cycle-us changes the
cycle, --axes-per-bus the axes on a bus: at 1 ms a 1 Mbit/s bus carries two, the machine
file's 70 % load limit). Every channel runs the same program, two all-channel G04.1 marks and two moves of X
and Z, about 3 600 cycles at 2 ms. For each N it runs the machine with `mcnc run`:
  - in lockstep: cycles, wall time of the whole run and of its run phase (from the launcher's
    "starting the run" to its verdict), times real time over each, and CPU (user plus system
    of the whole run, start-up included) per machine cycle and per channel;
  - in realtime at the same cycle: whether the run ends without alarm, the share of one core
    it took, and its alarms (a deadline missed ends in a quick stop, alarm 2006). The realtime
    program dwells after its moves so that the run lasts --realtime-s seconds (default 60);
    every axis still gets its setpoint every cycle while it dwells.
Each N runs on every middleware named (`machine.middleware`), and with every DDS Security
protection named (--protection: `off`, or `mcnc certs --protection` access, sign, encrypt), one
after the other, so that their rows are side by side in one go. Each run has a DDS domain of
its own from 60 on, or --domain D's (D in lockstep, D + 1 in realtime) for every run. On Cyclone DDS the launcher starts the host's RouDi
unless one answers (its start is in the whole run, not in the run phase).
Figures, not a test: bench/README.md has them with this command.

Usage: bench/scale.py [--build DIR] [--no-realtime] [--middleware fastdds,cyclonedds]
                      [--protection off,access,sign,encrypt] [--domain D] [--start-timeout S]
                      [--axes 2|4] [--cycle-us US] [--axes-per-bus K] [--realtime-s S]
                      [N ...]
       (default N: 1 2 4 8 16)
"""
import argparse
import os
import re
import resource
import subprocess
import sys
import tempfile
import time

from bench_machine import machine_yaml

HERE = os.path.dirname(os.path.abspath(__file__))
# Two moves of 42 mm at 12 mm/s, each after a mark every channel meets: about 3 600 cycles.
PROGRAM = """%
O0001 (scale bench)
G04.1 P1
G01 X30. Z-30. F720
G04.1 P2
G01 X0 Z0 F720
{dwell}M30
%
"""


def run(build, channels, clock, domain, middleware, axes, cycle_us, per_bus, dwell_s,
        protection="off", start_timeout=None):
    with tempfile.TemporaryDirectory() as tmp:
        machine = os.path.join(tmp, "m.yaml")
        with open(machine, "w") as f:
            f.write(machine_yaml(f"scale_{channels}", channels, axes, cycle_us, domain,
                                 deadline_cycles=10, middleware=middleware,
                                 axes_per_bus=per_bus))
        if protection != "off":
            subprocess.run([os.path.join(build, "bin", "mcnc"), "certs", machine,
                            os.path.join(tmp, "certs"), "--protection", protection],
                           check=True, stdout=subprocess.DEVNULL)
            with open(machine) as f:
                text = f.read()
            with open(machine, "w") as f:
                f.write(text.replace("machine:\n", "machine:\n  security_dir: certs\n", 1))
        prog = os.path.join(tmp, "p.nc")
        with open(prog, "w") as f:
            f.write(PROGRAM.format(dwell=f"G04 X{dwell_s:.1f}\n" if dwell_s > 0 else ""))
        trace = os.path.join(tmp, "t.jsonl")
        argv = [os.path.join(build, "bin", "mcnc"), "run", machine, "--clock", clock,
                "--trace", trace, "--trace-pos-every", "1000", "--timeout", "600"]
        if start_timeout is not None:
            argv += ["--start-timeout", str(start_timeout)]
        for c in range(1, channels + 1):
            argv += ["--program", f"CH{c}={prog}"]
        env = dict(os.environ, MCNC_DOMAIN=str(domain))
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.monotonic()
        run_start = None
        out = []
        with subprocess.Popen(argv, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              text=True) as p:
            for line in p.stdout:
                out.append(line)
                if run_start is None and "starting the run" in line:
                    run_start = time.monotonic()
                    # How long the start took (the handshakes of a secured machine), on stderr.
                    print(f"N = {channels} {protection} ({clock}): ready "
                          f"{run_start - start:.0f} s after the start", file=sys.stderr,
                          flush=True)
            code = p.wait()
        end = time.monotonic()
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        text = "".join(out)
        m = re.search(r"^ok after (\d+) cycles$", text, re.M)
        alarms = sorted(set(re.findall(r"alarm (\d{4})", text)))
        cycles = int(m.group(1)) if m else None
        if cycles is None:
            m = re.search(r"after (\d+) cycles", text)
            cycles = int(m.group(1)) if m else 0
        return {"code": code, "cycles": cycles, "wall": end - start,
                "run": end - (run_start or start), "cpu": cpu, "alarms": alarms,
                "tail": text[-1500:], "text": text}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(HERE, "..", "build"))
    ap.add_argument("--no-realtime", action="store_true")
    ap.add_argument("--middleware", default="fastdds,cyclonedds")
    ap.add_argument("--protection", default="off")
    ap.add_argument("--domain", type=int, default=None)
    ap.add_argument("--start-timeout", type=float, default=None)
    ap.add_argument("--axes", type=int, choices=[2, 4], default=2)
    ap.add_argument("--cycle-us", type=int, default=2000)
    ap.add_argument("--axes-per-bus", type=int, default=4)
    ap.add_argument("--realtime-s", type=float, default=60.0)
    ap.add_argument("channels", type=int, nargs="*", default=[1, 2, 4, 8, 16])
    args = ap.parse_args()
    cycle_us = args.cycle_us
    # The moves take about 7.2 s; the dwell makes up the rest of the realtime run.
    dwell_s = max(0.0, args.realtime_s - 7.2)
    print(f"| N channels × {args.axes} axes | middleware | protection | cycles | lockstep: times real time "
          f"(whole run / run phase) | CPU per machine cycle | per channel "
          f"| realtime {cycle_us / 1000:g} ms, {args.realtime_s:g} s |")
    print("|---|---|---|---|---|---|---|---|")
    for i, (n, mw, pr) in enumerate((n, mw, pr) for n in args.channels
                                    for mw in args.middleware.split(",")
                                    for pr in args.protection.split(",")):
        domain = 60 + 2 * i if args.domain is None else args.domain
        lock = run(args.build, n, "lockstep", domain, mw, args.axes, cycle_us,
                   args.axes_per_bus, 0.0, pr, args.start_timeout)
        if lock["code"] != 0 or lock["cycles"] == 0:
            print(f"| {n} | {mw} | {pr} | the lockstep run failed (exit {lock['code']}) "
                  f"| | | | |", flush=True)
            print("".join(re.findall(r"^failed:.*\n", lock["text"], re.M)) + lock["tail"],
                  file=sys.stderr)
            continue
        machine_s = lock["cycles"] * cycle_us / 1e6
        per_cycle = lock["cpu"] / lock["cycles"] * 1e6
        realtime = "not run"
        if not args.no_realtime:
            rt = run(args.build, n, "realtime", domain + 1, mw, args.axes, cycle_us,
                     args.axes_per_bus, dwell_s, pr, args.start_timeout)
            share = 100 * rt["cpu"] / rt["wall"]
            if rt["code"] == 0:
                realtime = f"runs, {share:.0f} % of one core"
            else:
                realtime = (f"fails after {rt['cycles']} cycles (alarms {', '.join(rt['alarms'])}),"
                            f" {share:.0f} % of one core")
        print(f"| {n} | {mw} | {pr} | {lock['cycles']} | {machine_s / lock['wall']:.2f} × / "
              f"{machine_s / lock['run']:.2f} × | {per_cycle:.0f} µs | {per_cycle / n:.0f} µs "
              f"| {realtime} |", flush=True)


if __name__ == "__main__":
    main()
