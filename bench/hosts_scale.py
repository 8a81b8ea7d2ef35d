#!/usr/bin/env python3
"""Hosts x channels that run at 2 ms (issue 22): N channels of two axes (bench_machine's scale
machine, one CAN bus per channel) spread over H simulated hosts (tests/hosts/hostnet.py:
network, mount and time namespaces), realtime, a launcher on each host.

Channel c runs on host (c - 1) mod H; its bus (can(c - 1), its X and Z) is wired to the next
host, so that with H > 1 every axis is a link axis: its channel on one host, its node and drive
on another (the worst case for the link). Every channel runs
bench/scale.py's program (two all-channel G04.1 marks, two moves) and dwells to last --seconds.
A pair (H, N) runs at 2 ms when the coordinator's run ends without an alarm. The host clocks are
offset by +3 ms per host (time namespaces), as in the tests.

usage: bench/hosts_scale.py [--build DIR] [--seconds S] [--domain D] H:N [H:N ...]
       (root: it makes namespaces; e.g. 2:2 2:4 3:3 3:6)
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

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HOSTNET = os.path.join(SOURCE, "tests", "hosts", "hostnet.py")
PROGRAM = """%
O0001 (hosts scale bench)
G04.1 P1
G01 X30. Z-30. F720
G04.1 P2
G01 X0 Z0 F720
G04 X{dwell:.1f}
M30
%
"""
AXES_PER_BUS = 2  # one channel's X and Z


def hosts_yaml(hosts, channels):
    names = [f"ncu{h + 1}" for h in range(hosts)]
    runs = {name: [] for name in names}
    for c in range(1, channels + 1):
        runs[names[(c - 1) % hosts]].append(f"CH{c}")
    axes = [f"{a}{c}" for c in range(1, channels + 1) for a in ("X", "Z")]
    for b in range(channels):
        host = names[(b + 1) % hosts]  # the host after its channel's
        runs[host].append(f"can{b}")
        runs[host].extend(axes[b * AXES_PER_BUS:(b + 1) * AXES_PER_BUS])
    lines = ["hosts:"]
    for name in names:
        lines.append(f"  - {{name: {name}, runs: [{', '.join(runs[name])}]}}")
    return names, "\n".join(lines) + "\n"


def run(build, hosts, channels, seconds, domain):
    prefix = f"mhs{domain}"
    mcnc = os.path.join(build, "bin", "mcnc")
    with tempfile.TemporaryDirectory(dir=os.path.join(build)) as tmp:
        names, hosts_section = hosts_yaml(hosts, channels)
        machine = os.path.join(tmp, "m.yaml")
        with open(machine, "w") as f:
            f.write(machine_yaml(f"hosts_scale_{hosts}x{channels}", channels, 2, 2000, domain,
                                 deadline_cycles=10, middleware="cyclonedds",
                                 axes_per_bus=AXES_PER_BUS) + hosts_section)
        prog = os.path.join(tmp, "p.nc")
        with open(prog, "w") as f:
            f.write(PROGRAM.format(dwell=seconds))
        offsets = ",".join(f"{n}={3 * i}" for i, n in enumerate(names) if i > 0)
        subprocess.run([sys.executable, HOSTNET, "up", "--prefix", prefix, "--hosts",
                        ",".join(names), "--subnet", f"10.77.{domain}"]
                       + (["--offset-ms", offsets] if offsets else []),
                       check=True, capture_output=True)
        env = dict(os.environ, MCNC_DOMAIN=str(domain))
        try:
            def launcher(host):
                argv = [sys.executable, HOSTNET, "exec", "--prefix", prefix, host, "--", mcnc,
                        "run", machine, "--clock", "realtime", "--timeout",
                        str(int(seconds) + 120), "--host", host]
                for c in range(1, channels + 1):
                    argv += ["--program", f"CH{c}={prog}"]
                return argv
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            start = time.monotonic()
            followers = [subprocess.Popen(launcher(h), stdout=subprocess.DEVNULL,
                                          stderr=subprocess.DEVNULL, env=env)
                         for h in names[1:]]
            r = subprocess.run(launcher(names[0]), capture_output=True, text=True, env=env)
            for f in followers:
                f.wait(timeout=180)
            wall = time.monotonic() - start
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
        finally:
            subprocess.run([sys.executable, HOSTNET, "down", "--prefix", prefix],
                           capture_output=True)
    text = r.stdout + r.stderr
    alarms = sorted(set(re.findall(r"alarm:? (?:[\w-]+ )?(\d{4})", text)))
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return {"code": r.returncode, "alarms": alarms, "wall": wall, "cpu": cpu,
            "tail": text[-1200:]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(SOURCE, "build"))
    ap.add_argument("--seconds", type=float, default=30.0)
    ap.add_argument("--domain", type=int, default=206)
    ap.add_argument("pairs", nargs="+", help="H:N, hosts and channels")
    args = ap.parse_args()
    os.chdir(SOURCE)
    print("hosts | channels | axes | exit | alarms | wall | CPU share of the 2 cores")
    for pair in args.pairs:
        hosts, channels = (int(x) for x in pair.split(":"))
        res = run(args.build, hosts, channels, args.seconds, args.domain)
        share = res["cpu"] / res["wall"] / (os.cpu_count() or 1) * 100
        print(f"{hosts} | {channels} | {2 * channels} | {res['code']} | "
              f"{','.join(res['alarms']) or 'none'} | {res['wall']:.1f} s | {share:.0f} %",
              flush=True)
        if res["code"] != 0:
            print("  " + res["tail"].replace("\n", "\n  "), flush=True)


if __name__ == "__main__":
    main()
