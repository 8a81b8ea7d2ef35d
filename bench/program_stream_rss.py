#!/usr/bin/env python3
"""Memory of a long program (issue 23, "programs stream"): a generated program of about 100 MB
(4 M blocks) run by `mcnc interp` to its end, and by the channel of small_lathe.yaml (`mcnc run`,
lockstep) for a while. Prints the program's size, `mcnc interp`'s peak RSS and time, and the
channel's peak RSS (VmHWM) once its program runs, sampled from /proc.

usage: bench/program_stream_rss.py [--mb 100] [--run-seconds 30] [--build DIR]
"""
import argparse
import os
import resource
import signal
import subprocess
import sys
import time

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def write_program(path, megabytes):
    """N numbers, feeds along X and Z back and forth, a comment now and then: 25 bytes a block."""
    target = megabytes * 1000 * 1000
    written = 0
    blocks = 0
    with open(path, "w") as f:
        f.write("O0001 (stream bench)\nG18 G99 G21\nG00 X20 Z1\nG98 G01 F3000\n")
        while written < target:
            lines = []
            for k in range(1000):
                n = blocks + k
                x = 20 + (n % 50) * 0.01
                z = -(n % 40) * 0.01
                lines.append("N%d X%.2f Z%.2f\n" % (n % 99999 + 1, x, z))
            chunk = "".join(lines)
            f.write(chunk)
            written += len(chunk)
            blocks += 1000
        f.write("M30\n")
    return blocks, os.path.getsize(path)


def status_kb(pid, key):
    try:
        with open("/proc/%d/status" % pid) as f:
            for line in f:
                if line.startswith(key + ":"):
                    return int(line.split()[1])
    except OSError:
        pass
    return None


def channel_pid(needle):
    for name in os.listdir("/proc"):
        if not name.isdigit():
            continue
        try:
            with open("/proc/%s/cmdline" % name, "rb") as f:
                cmd = f.read().replace(b"\0", b" ").decode(errors="replace")
        except OSError:
            continue
        if "mcnc-channel" in cmd and needle in cmd:
            return int(name)
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--mb", type=int, default=100)
    parser.add_argument("--run-seconds", type=float, default=30)
    parser.add_argument("--build", default=os.path.join(SOURCE, "build"))
    args = parser.parse_args()
    work = os.path.join(args.build, "bench-stream")
    os.makedirs(work, exist_ok=True)
    program = os.path.join(work, "long.nc")
    blocks, size = write_program(program, args.mb)
    print("program: %d blocks, %.1f MB" % (blocks, size / 1e6))

    mcnc = os.path.join(args.build, "bin", "mcnc")
    start = time.monotonic()
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    r = subprocess.run([mcnc, "interp", program], stdout=subprocess.DEVNULL,
                       stderr=subprocess.PIPE, text=True)
    seconds = time.monotonic() - start
    peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    if r.returncode != 0:
        raise SystemExit("mcnc interp failed: " + r.stderr[-2000:])
    print("mcnc interp: peak RSS %.1f MB, %.1f s (%.0f blocks/s)%s"
          % (peak / 1024, seconds, blocks / seconds,
             "" if peak > before else " (peak not above an earlier child's)"))

    # The channel: the launcher runs it in lockstep; sample its RSS while the program runs.
    env = dict(os.environ, MCNC_DOMAIN="143")
    launcher = subprocess.Popen(
        [mcnc, "run", "launch/machines/small_lathe.yaml", "--program", "CH1=" + program,
         "--timeout", str(int(args.run_seconds + 120))],
        cwd=SOURCE, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    pid = None
    deadline = time.monotonic() + 120
    while pid is None and time.monotonic() < deadline and launcher.poll() is None:
        pid = channel_pid(program)
        time.sleep(0.2)
    if pid is None:
        launcher.kill()
        raise SystemExit("no channel process: " + launcher.stderr.read()[-2000:])
    started = time.monotonic()
    samples = []
    while time.monotonic() - started < args.run_seconds and launcher.poll() is None:
        rss = status_kb(pid, "VmRSS")
        if rss is not None:
            samples.append(rss)
        time.sleep(0.5)
    hwm = status_kb(pid, "VmHWM")
    launcher.send_signal(signal.SIGINT)
    try:
        launcher.wait(timeout=60)
    except subprocess.TimeoutExpired:
        launcher.kill()
    if not samples or hwm is None:
        raise SystemExit("the channel ended before it was sampled")
    print("channel: peak RSS (VmHWM) %.1f MB over %.0f s from its start (check and run); "
          "RSS at the end %.1f MB" % (hwm / 1024, args.run_seconds, samples[-1] / 1024))
    os.remove(program)


if __name__ == "__main__":
    sys.exit(main())
