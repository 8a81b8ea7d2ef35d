#!/usr/bin/env python3
"""Simulated controller hosts on one machine, for the tests of a machine across hosts.

Each host is a network namespace joined by a veth pair to a bridge in a namespace of its own
(the "switch"), with a mount namespace of its own (private /tmp and /dev/shm, so that shared
memory and iceoryx's RouDi stay on their host) and a time namespace of its own (its
CLOCK_MONOTONIC shifted by the offset the test asks for). A keeper process per host holds the
namespaces; commands enter them with nsenter. Everything made is recorded in a state directory
as it is made, so that `down` removes it all, also after a failure half-way.

  hostnet.py up   --prefix P --hosts a,b[,...] [--offset-ms a=3,b=-7] [--subnet 10.77.0]
  hostnet.py exec --prefix P HOST -- CMD [ARG...]
  hostnet.py addr --prefix P HOST          (the host's address on the bridge)
  hostnet.py cut  --prefix P HOST          (HOST and the others no longer hear each other)
  hostnet.py loss --prefix P PERCENT       (every host drops that share of what others send it)
  hostnet.py heal --prefix P               (no cut, no loss)
  hostnet.py down --prefix P

Needs root, iproute2, iptables and util-linux (nsenter). Only addresses of the namespaces made here
carry traffic: the switch has no link to the machine's own network.
"""
import argparse
import ctypes
import json
import os
import signal
import subprocess
import sys
import time

STATE_ROOT = "/run/mcnc-hosts"
CLONE_NEWNS = 0x00020000
CLONE_NEWNET = 0x40000000
CLONE_NEWTIME = 0x00000080

libc = ctypes.CDLL(None, use_errno=True)


def run(*cmd):
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)


def state_dir(prefix):
    return os.path.join(STATE_ROOT, prefix)


def load_state(prefix):
    try:
        with open(os.path.join(state_dir(prefix), "state.json")) as f:
            return json.load(f)
    except FileNotFoundError:
        return {"netns": [], "keepers": {}, "addresses": {}}


def save_state(prefix, state):
    os.makedirs(state_dir(prefix), exist_ok=True)
    path = os.path.join(state_dir(prefix), "state.json")
    with open(path + ".new", "w") as f:
        json.dump(state, f)
    os.replace(path + ".new", path)


def keeper(netns, offset_ns, ready_fd):
    """Runs in a child of `up`: enters the host's network namespace, makes its mount and time
    namespaces, then forks the process that holds them (its pid goes to `ready_fd`)."""
    fd = os.open("/run/netns/" + netns, os.O_RDONLY)
    if libc.setns(fd, CLONE_NEWNET) != 0:
        raise OSError(ctypes.get_errno(), "setns " + netns)
    os.close(fd)
    if libc.unshare(CLONE_NEWNS | CLONE_NEWTIME) != 0:
        raise OSError(ctypes.get_errno(), "unshare mount and time namespaces")
    # The offsets can be set only before any process is in the new time namespace.
    seconds, nanos = divmod(offset_ns, 1_000_000_000)
    with open("/proc/self/timens_offsets", "w") as f:
        f.write("monotonic %d %d\n" % (seconds, nanos))
    run("mount", "--make-rprivate", "/")
    for path in ("/tmp", "/dev/shm"):
        run("mount", "-t", "tmpfs", "-o", "mode=1777", "tmpfs", path)
    pid = os.fork()
    if pid == 0:
        os.setsid()
        # It holds no pipe of whoever ran `up` open: their reads end when `up` ends.
        null = os.open(os.devnull, os.O_RDWR)
        for fd in (0, 1, 2):
            os.dup2(null, fd)
        os.closerange(3, 1024)
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        while True:
            signal.pause()
    os.write(ready_fd, str(pid).encode())
    os._exit(0)


def up(args):
    hosts = [h for h in args.hosts.split(",") if h]
    offsets = {}
    for item in filter(None, (args.offset_ms or "").split(",")):
        name, value = item.split("=")
        offsets[name] = round(float(value) * 1_000_000)
    state = load_state(args.prefix)
    p = args.prefix
    switch = p + "-sw"
    run("ip", "netns", "add", switch)
    state["netns"].append(switch)
    save_state(args.prefix, state)
    run("ip", "-n", switch, "link", "set", "lo", "up")
    run("ip", "-n", switch, "link", "add", "br0", "type", "bridge")
    run("ip", "-n", switch, "link", "set", "br0", "up")
    for i, host in enumerate(hosts):
        netns = p + "-" + host
        run("ip", "netns", "add", netns)
        state["netns"].append(netns)
        save_state(args.prefix, state)
        port = ("%s%d" % (p, i))[-13:] + "p"
        run("ip", "link", "add", "eth0", "netns", netns, "type", "veth", "peer", "name", port,
            "netns", switch)
        address = "%s.%d" % (args.subnet, i + 1)
        run("ip", "-n", netns, "link", "set", "lo", "up")
        run("ip", "-n", netns, "addr", "add", address + "/24", "dev", "eth0")
        run("ip", "-n", netns, "link", "set", "eth0", "up")
        # Multicast (DDS discovery, the simulated CAN buses) leaves by the host's one interface.
        run("ip", "-n", netns, "route", "add", "224.0.0.0/4", "dev", "eth0")
        run("ip", "-n", switch, "link", "set", port, "master", "br0", "up")
        state["addresses"][host] = address
        r, w = os.pipe()
        child = os.fork()
        if child == 0:
            os.close(r)
            try:
                keeper(netns, offsets.get(host, 0), w)
            except BaseException as e:  # noqa: BLE001 - reported to the parent by the pipe's end
                print("hostnet: host %s: %s" % (host, e), file=sys.stderr)
                os._exit(1)
        os.close(w)
        pid_text = os.read(r, 32).decode()
        os.close(r)
        _, status = os.waitpid(child, 0)
        if not pid_text or status != 0:
            raise SystemExit("hostnet: host %s could not be made" % host)
        state["keepers"][host] = int(pid_text)
        save_state(args.prefix, state)
    print(json.dumps(state["addresses"]))


def enter(prefix, host):
    state = load_state(prefix)
    if host not in state["keepers"]:
        raise SystemExit("hostnet: no host %s in %s" % (host, prefix))
    # The working directory stays (a host sees the machine's files, except /tmp and /dev/shm).
    return ["nsenter", "-t", str(state["keepers"][host]), "--net", "--mount", "--time",
            "--wd=" + os.getcwd(), "--"]


def exec_(args):
    cmd = args.cmd[1:] if args.cmd and args.cmd[0] == "--" else args.cmd
    os.execvp("nsenter", enter(args.prefix, args.host) + cmd)


def addr(args):
    print(load_state(args.prefix)["addresses"][args.host])


def filter_input(prefix, host, rule):
    """Appends an iptables rule to the INPUT chain of `host`'s network namespace."""
    run("ip", "netns", "exec", prefix + "-" + host, "iptables", "-w", "-A", "INPUT", *rule)


def cut(args):
    # By source address, on input: a host's own multicast comes back to it on its interface
    # (the simulated CAN buses), and must go on arriving; what a host sends out still reaches
    # the switch, where nobody takes it.
    addresses = load_state(args.prefix)["addresses"]
    if args.host not in addresses:
        raise SystemExit("hostnet: no host %s in %s" % (args.host, args.prefix))
    for host, address in addresses.items():
        if host == args.host:
            for other, other_address in addresses.items():
                if other != host:
                    filter_input(args.prefix, host, ["-s", other_address, "-j", "DROP"])
        else:
            filter_input(args.prefix, host, ["-s", addresses[args.host], "-j", "DROP"])


def loss(args):
    addresses = load_state(args.prefix)["addresses"]
    probability = "%.6f" % (float(args.percent) / 100)
    for host in addresses:
        for other, other_address in addresses.items():
            if other != host:
                filter_input(args.prefix, host, ["-s", other_address, "-m", "statistic",
                                                 "--mode", "random", "--probability",
                                                 probability, "-j", "DROP"])


def heal(args):
    for host in load_state(args.prefix)["addresses"]:
        run("ip", "netns", "exec", args.prefix + "-" + host, "iptables", "-w", "-F", "INPUT")


def down(args):
    state = load_state(args.prefix)
    failed = False
    for host, pid in state["keepers"].items():
        # Every process still inside the host's namespaces goes with it.
        try:
            mnt = os.readlink("/proc/%d/ns/mnt" % pid)
        except OSError:
            mnt = None
        if mnt is not None:
            for other in os.listdir("/proc"):
                if other.isdigit() and int(other) != os.getpid():
                    try:
                        if os.readlink("/proc/%s/ns/mnt" % other) == mnt:
                            os.kill(int(other), signal.SIGKILL)
                    except OSError:
                        pass
    deadline = time.monotonic() + 5
    for pid in state["keepers"].values():
        while time.monotonic() < deadline and os.path.exists("/proc/%d" % pid):
            time.sleep(0.02)
    for netns in reversed(state["netns"]):
        if subprocess.run(["ip", "netns", "del", netns], stderr=subprocess.DEVNULL).returncode:
            failed = failed or os.path.exists("/run/netns/" + netns)
    try:
        os.remove(os.path.join(state_dir(args.prefix), "state.json"))
        os.rmdir(state_dir(args.prefix))
    except OSError:
        pass
    if failed:
        raise SystemExit("hostnet: some namespaces of %s could not be removed" % args.prefix)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="verb", required=True)
    p_up = sub.add_parser("up")
    p_up.add_argument("--prefix", required=True)
    p_up.add_argument("--hosts", required=True)
    p_up.add_argument("--offset-ms")
    p_up.add_argument("--subnet", default="10.77.0")
    p_exec = sub.add_parser("exec")
    p_exec.add_argument("--prefix", required=True)
    p_exec.add_argument("host")
    p_exec.add_argument("cmd", nargs=argparse.REMAINDER)
    p_addr = sub.add_parser("addr")
    p_addr.add_argument("--prefix", required=True)
    p_addr.add_argument("host")
    p_cut = sub.add_parser("cut")
    p_cut.add_argument("--prefix", required=True)
    p_cut.add_argument("host")
    p_loss = sub.add_parser("loss")
    p_loss.add_argument("--prefix", required=True)
    p_loss.add_argument("percent")
    p_heal = sub.add_parser("heal")
    p_heal.add_argument("--prefix", required=True)
    p_down = sub.add_parser("down")
    p_down.add_argument("--prefix", required=True)
    args = parser.parse_args()
    if len(args.prefix) > 8 or not args.prefix.replace("-", "").isalnum():
        raise SystemExit("hostnet: a prefix has at most 8 letters and digits")
    {"up": up, "exec": exec_, "addr": addr, "cut": cut, "loss": loss, "heal": heal,
     "down": down}[args.verb](args)


if __name__ == "__main__":
    main()
