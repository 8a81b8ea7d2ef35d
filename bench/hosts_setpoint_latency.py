#!/usr/bin/env python3
"""Link-axis setpoint latency across hosts (issue 22): channel write -> the drive's RPDO.

bench/setpoint_latency.cpp plays the channel of launch/machines/small_lathe.yaml at a 2 ms cycle
and times each setpoint from its write to the axis node's RPDO on the bus. Here it runs on a
simulated host `a` (tests/hosts/hostnet.py) while the drive simulator and the axis nodes run:
1. on `a` too (the one-host figure, same conditions);
2. on host `b`: the setpoints cross the network, and the bus is listened to from inside `b`'s
   network namespace by a thread of the bench, so both times are on one clock.
Each host has its own iceoryx RouDi. Clocks are not offset here (the alignment across clocks is
bench/hosts_realtime.py's).

usage: bench/hosts_setpoint_latency.py [--build DIR] [--cycles N]    (root)
"""
import argparse
import datetime
import json
import os
import re
import subprocess
import sys
import time

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HOSTNET = os.path.join(SOURCE, "tests", "hosts", "hostnet.py")
PREFIX = "mhl"


def machine_file(work):
    with open(os.path.join(SOURCE, "launch", "machines", "small_lathe.yaml")) as f:
        text = f.read()
    text = re.sub(r"udp:[0-9.]*:[0-9]*", "udp:239.255.79.1:24079", text)
    text = text.replace("cycle_us: 1000", "cycle_us: 2000")
    text = text.replace("deadline_cycles: 20", "deadline_cycles: 100")
    path = os.path.join(work, "latency.yaml")
    with open(path, "w") as f:
        f.write(text)
    return path


def on(host, argv):
    return [sys.executable, HOSTNET, "exec", "--prefix", PREFIX, host, "--", *argv]


def measure(bench, machine, cycles, nodes_host):
    argv = [bench, machine, "--cycles", str(cycles)]
    if nodes_host != "a":
        # By the host's keeper process: /run/netns of a host made later is not mounted in the
        # mount namespace of one made earlier.
        with open("/run/mcnc-hosts/%s/state.json" % PREFIX) as f:
            keeper = json.load(f)["keepers"][nodes_host]
        argv += ["--nodes-prefix", " ".join(on(nodes_host, [])),
                 "--bus-netns", "/proc/%d/ns/net" % keeper]
    r = subprocess.run(on("a", argv), capture_output=True, text=True,
                       env=dict(os.environ, MCNC_DOMAIN="79"))
    return (r.stdout + r.stderr).strip()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(SOURCE, "build"))
    parser.add_argument("--cycles", type=int, default=10000)
    args = parser.parse_args()
    bench = os.path.join(args.build, "bin", "mcnc_bench_setpoint_latency")
    work = os.path.join(args.build, "bench-hosts-latency")
    os.makedirs(work, exist_ok=True)
    os.chdir(SOURCE)
    machine = machine_file(work)
    subprocess.run([sys.executable, HOSTNET, "down", "--prefix", PREFIX], capture_output=True)
    subprocess.run([sys.executable, HOSTNET, "up", "--prefix", PREFIX, "--hosts", "a,b",
                    "--subnet", "10.77.79"], check=True, capture_output=True)
    roudis = []
    try:
        for host in ("a", "b"):
            roudis.append(subprocess.Popen(
                on(host, ["iox-roudi", "-c", "tests/roudi/roudi_config.toml", "-l", "warning"]),
                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        time.sleep(2)
        print("date %s, small_lathe at 2 ms, %d cycles" % (datetime.date.today(), args.cycles))
        for where in ("a", "b"):
            print("axis node and drive on host %s:" % where)
            print(measure(bench, machine, args.cycles, where))
    finally:
        for r in roudis:
            r.terminate()
        for r in roudis:
            r.wait(timeout=10)
        subprocess.run([sys.executable, HOSTNET, "down", "--prefix", PREFIX])


if __name__ == "__main__":
    main()
