#!/usr/bin/env python3
"""Wake-ups and CPU of the running mcnc processes over a few seconds, from /proc: for each
program, how many processes, their voluntary context switches per second (each one a wait that
ended: a wake-up) and their CPU share of one core. Run it beside a machine run; divide by the
machine's cycles per second for the figures per cycle.

With --threads, one row per program and thread: the main thread (the cycle's), ours by their
names (can-rx, can-sync, alarms, trace, program-loader), the middleware's by theirs (Cyclone
DDS: recv, recvUC, tev, dq.builtins, gc; iceoryx: KeepAlive) and a library's unnamed ones
(Cyclone DDS's shared-memory listener), so that the wake-ups can be told apart.

Usage: bench/thread_wakeups.py [--threads] [SECONDS]   (default 5)
"""
import collections
import os
import sys
import time

TICKS = os.sysconf("SC_CLK_TCK")


def snapshot(by_thread):
    threads = {}
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/comm") as f:
                program = f.read().strip()
            if not program.startswith("mcnc"):
                continue
            for tid in os.listdir(f"/proc/{pid}/task"):
                with open(f"/proc/{pid}/task/{tid}/status") as f:
                    status = f.read()
                with open(f"/proc/{pid}/task/{tid}/stat") as f:
                    fields = f.read().rsplit(")", 1)[1].split()
                switches = int(status.split("voluntary_ctxt_switches:")[1].split()[0])
                cpu_ticks = int(fields[11]) + int(fields[12])  # utime + stime
                name = program
                if by_thread:
                    with open(f"/proc/{pid}/task/{tid}/comm") as f:
                        thread = f.read().strip()
                    # Our threads carry names (common/process/thread_name.hpp); a thread that
                    # kept the program's name and is not the main one is a library's.
                    if tid == pid:
                        thread = "main (the cycle)"
                    elif thread == program:
                        thread = "unnamed (a library's)"
                    name = f"{program} / {thread}"
                threads[(name, pid, tid)] = (switches, cpu_ticks)
        except (FileNotFoundError, ProcessLookupError, IndexError):
            continue  # a thread that ended meanwhile
    return threads


def main():
    args = sys.argv[1:]
    by_thread = "--threads" in args
    args = [a for a in args if a != "--threads"]
    seconds = float(args[0]) if args else 5.0
    before = snapshot(by_thread)
    time.sleep(seconds)
    after = snapshot(by_thread)
    totals = collections.defaultdict(lambda: [0, 0, set()])
    for key, (switches, ticks) in after.items():
        if key in before:
            t = totals[key[0]]
            t[0] += switches - before[key][0]
            t[1] += ticks - before[key][1]
            t[2].add(key[1])
    print(f"| {'program / thread' if by_thread else 'program'} | processes "
          "| wake-ups per second | CPU, % of one core |")
    print("|---|---|---|---|")
    for program, (switches, ticks, pids) in sorted(totals.items(), key=lambda kv: -kv[1][1]):
        print(f"| {program} | {len(pids)} | {switches / seconds:.0f} "
              f"| {100 * ticks / TICKS / seconds:.1f} |")


if __name__ == "__main__":
    main()
