#!/usr/bin/env python3
"""The simulated hosts of the tests of a machine across hosts (tests/hosts/hostnet.py), checked
for what those tests rely on: each host's clock runs at the offset asked for, its /tmp and
/dev/shm are its own, the hosts reach each other and nothing else, a machine on one host (with
its own RouDi) is seen over DDS from another, and `down` removes everything, also after an `up`
that failed half-way.

usage: hosts_test.py BUILD_DIR
"""
import json
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(os.path.dirname(HERE))
HOSTNET = os.path.join(HERE, "hostnet.py")
PREFIX = "mht%d" % (os.getpid() % 10000)
SUBNET = "10.77.%d" % (os.getpid() % 200 + 20)
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


def hostnet(*args, **kw):
    return subprocess.run([sys.executable, HOSTNET, args[0], "--prefix", PREFIX, *args[1:]],
                          capture_output=True, text=True, **kw)


def on(host, *cmd, env=None, timeout=60):
    return subprocess.run([sys.executable, HOSTNET, "exec", "--prefix", PREFIX, host, "--", *cmd],
                          capture_output=True, text=True, env=env, timeout=timeout)


# CLOCK_MONOTONIC minus CLOCK_BOOTTIME: a time namespace shifts the first only (hostnet sets
# no boottime offset), so the difference between a host's and the machine's is its offset,
# however long the process took to start. A preemption between the two reads makes one
# difference smaller, never larger: the largest of many is the true one, to the microsecond.
MONO_MINUS_BOOT = ("import time; print(max(time.clock_gettime_ns(time.CLOCK_MONOTONIC) - "
                   "time.clock_gettime_ns(time.CLOCK_BOOTTIME) for _ in range(1000)))")


def clock_offset_ns(host):
    here = int(subprocess.run([sys.executable, "-c", MONO_MINUS_BOOT], capture_output=True,
                              text=True).stdout)
    there = int(on(host, sys.executable, "-c", MONO_MINUS_BOOT).stdout)
    return there - here


def namespaces():
    r = subprocess.run(["ip", "netns", "list"], capture_output=True, text=True)
    return [line.split()[0] for line in r.stdout.splitlines() if line.startswith(PREFIX + "-")]


def main():
    build = os.path.abspath(sys.argv[1])
    os.chdir(SOURCE)
    try:
        r = hostnet("up", "--hosts", "a,b", "--offset-ms", "a=3,b=-7", "--subnet", SUBNET)
        check(r.returncode == 0, "up makes two hosts: " + r.stderr.strip())
        addresses = json.loads(r.stdout)
        check(addresses == {"a": SUBNET + ".1", "b": SUBNET + ".2"}, "their addresses")
        check(sorted(namespaces()) == sorted([PREFIX + "-a", PREFIX + "-b", PREFIX + "-sw"]),
              "a network namespace per host and one for the switch")

        # Clocks: each host's CLOCK_MONOTONIC is the machine's plus its offset.
        for host, offset_ms in (("a", 3), ("b", -7)):
            measured = clock_offset_ns(host)
            check(abs(measured - offset_ms * 1_000_000) < 200_000,
                  "host %s's clock runs %+d ms from the machine's (measured %+.3f ms)" %
                  (host, offset_ms, measured / 1e6))

        # Files: /tmp and /dev/shm are the host's own.
        on("a", "sh", "-c", "echo a > /tmp/%s-mark && echo a > /dev/shm/%s-mark" % (PREFIX, PREFIX))
        seen_b = on("b", "sh", "-c", "ls /tmp /dev/shm").stdout
        check(PREFIX + "-mark" not in seen_b, "host b does not see host a's /tmp and /dev/shm")
        check(not os.path.exists("/tmp/%s-mark" % PREFIX) and
              not os.path.exists("/dev/shm/%s-mark" % PREFIX),
              "the machine does not see them either")
        check(on("a", "cat", "/tmp/%s-mark" % PREFIX).stdout.strip() == "a", "host a does")

        # Network: the hosts reach each other over the switch, and have no other way out.
        receive = ("import socket; s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM); "
                   "s.bind(('0.0.0.0', 5999)); s.settimeout(5); print(s.recvfrom(16)[0].decode())")
        listener = subprocess.Popen(
            [sys.executable, HOSTNET, "exec", "--prefix", PREFIX, "b", "--", sys.executable, "-c",
             receive], stdout=subprocess.PIPE, text=True)
        time.sleep(0.5)
        on("a", sys.executable, "-c",
           "import socket; socket.socket(socket.AF_INET, socket.SOCK_DGRAM)"
           ".sendto(b'from-a', ('%s.2', 5999))" % SUBNET)
        out, _ = listener.communicate(timeout=10)
        check(out.strip() == "from-a", "a datagram from host a reaches host b")
        routes = on("a", "ip", "route", "show").stdout
        check("default" not in routes, "a host has no route beyond the switch")

        # DDS across hosts: a machine on host a (lockstep, paced, its own RouDi in a's /tmp) is
        # seen from host b by `mcnc status`, on the other DDS implementation.
        env = dict(os.environ, MCNC_DOMAIN="9")
        machine = subprocess.Popen(
            [sys.executable, HOSTNET, "exec", "--prefix", PREFIX, "a", "--",
             os.path.join(build, "bin", "mcnc"), "run", "launch/machines/small_lathe.yaml",
             "--program", "CH1=launch/programs/long_feed.nc", "--pace", "--timeout", "30"],
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
        status = ""
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline and "running" not in status:
            time.sleep(1)
            status = on("b", os.path.join(build, "bin", "mcnc"), "status",
                        "launch/machines/small_lathe.yaml", "--wait-ms", "2000",
                        env=dict(env, MCNC_MIDDLEWARE="fastdds")).stdout
        check("CH1  running" in status, "host b sees CH1 running on host a:\n" + status)
        z = [line for line in status.splitlines() if line.startswith("Z1 ")]
        check(len(z) == 1 and "cmd 0.0000" not in z[0], "and its Z1 moving: %s" % z)
        roudis = on("a", "sh", "-c", "ls /tmp | grep -c roudi || true").stdout.strip()
        check(roudis not in ("", "0"), "the machine's RouDi keeps its files in host a's /tmp")
        machine.kill()
        machine.wait()

        # A second `up` of the same hosts fails at once and leaves them to `down`.
        again = hostnet("up", "--hosts", "a,b", "--subnet", SUBNET)
        check(again.returncode != 0, "a second up of the same prefix is refused")
    finally:
        # What still runs in host a (its keeper at least; pgrep sees the whole machine, so only
        # the processes of a's mount namespace): all of it goes with the host.
        inside = on("a", "sh", "-c",
                    "pgrep --nslist mnt --ns $$ . | grep -vx $$ || true").stdout.split()
        r = hostnet("down")
        check(r.returncode == 0, "down: " + r.stderr.strip())
        check(namespaces() == [], "no namespace of the test is left")
        check(not os.path.exists("/run/mcnc-hosts/" + PREFIX), "nor its state")
        time.sleep(0.5)
        alive = [pid for pid in inside if os.path.exists("/proc/" + pid)]
        check(inside and not alive,
              "what ran in host a went with it (%d processes, alive: %s)" % (len(inside), alive))
    if failures:
        print("%d check(s) failed" % len(failures))
        sys.exit(1)


if __name__ == "__main__":
    main()
