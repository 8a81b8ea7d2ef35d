#!/usr/bin/python3
"""Differential test: `mcnc interp` against LinuxCNC's rs274 on random lathe programs.

Each program (see progen.py) is written in both dialects and run by both interpreters; their
motion sequences (rapid/linear/arc end points, arc centres and directions, feeds, dwells) must
agree command by command. rs274 prints arc centres with 4 decimals only, so centres are compared
with rs274 within that resolution and with the generator's exact model within 1e-6; the model
itself is checked against rs274 on every program, so a harness error cannot pass silently.

    interp_vs_rs274.py --mcnc build/bin/mcnc [--seed S] [--count N] [--only I] [--keep DIR]

Exit code 0 when every program agrees, 1 otherwise (rs274 missing included: install it with
scripts/install-deps). A failure prints the seed, the program index, the command to reproduce
it, both program texts and the first differing command.
"""
from __future__ import annotations

import argparse
import collections
import re
import concurrent.futures
import os
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

sys.dont_write_bytecode = True   # no __pycache__ in the source tree
sys.path.insert(0, str(Path(__file__).resolve().parent))

import outputs  # noqa: E402
import progen   # noqa: E402

DEFAULT_SEED = "mcnc-1"
TIMEOUT_S = 30
IK_WORD = re.compile(r"\s[IK][-.\d#\[]")


@dataclass
class Result:
    index: int
    failure: str = ""           # empty: the program agrees
    commands: int = 0
    stats: collections.Counter | None = None


def run(cmd, stdin: str = "", env=None) -> subprocess.CompletedProcess:
    return subprocess.run(cmd, input=stdin, capture_output=True, text=True, timeout=TIMEOUT_S,
                          env=env)


def rs274_env(home: Path) -> dict:
    """rs274 truncates and maps $HOME/.tool.mmap at start: instances sharing a HOME crash each
    other (SIGBUS) when run in parallel, so each run gets its own."""
    home.mkdir(exist_ok=True)
    return {**os.environ, "HOME": str(home)}


def numbered(text: str) -> str:
    return "\n".join(f"{i:4} | {line}" for i, line in enumerate(text.splitlines(), 1))


def features(prog: progen.Program) -> collections.Counter:
    """What the program exercises, for the summary line."""
    text = prog.ours()
    stats = collections.Counter(m.op for m in prog.expected)
    stats["R<0 arcs"] = text.count(" R-")
    stats["I/K arcs"] = sum(1 for line in text.splitlines()
                            if IK_WORD.search(line) and not line.startswith("G65"))
    stats["U/W words"] = text.count(" U") + text.count(" W")
    stats["WHILE"] = text.count("WHILE")
    stats["IF GOTO"] = text.count("GOTO")
    stats["M98"] = text.count("M98")
    stats["G65"] = text.count("G65")
    stats["assignments"] = sum(1 for line in text.splitlines() if line.startswith("#"))
    return stats


def check_program(index: int, args, workdir: Path) -> Result:
    seed = f"{args.seed}/{index}"
    prog = progen.generate(seed)
    ours_text, lcnc_text = prog.ours(), prog.lcnc()
    ours_file, lcnc_file = workdir / f"p{index}.nc", workdir / f"p{index}.ngc"
    ours_file.write_text(ours_text)
    lcnc_file.write_text(lcnc_text)
    result = Result(index, commands=len(prog.expected), stats=features(prog))

    def fail(headline: str, detail: str) -> Result:
        result.failure = "\n".join([
            f"FAIL seed={args.seed} program={index}: {headline}",
            detail,
            f"reproduce: /usr/bin/python3 {Path(__file__).resolve()} --mcnc {args.mcnc} "
            f"--seed {args.seed} --only {index} --keep /tmp/interp_vs_rs274",
            f"--- mcnc interp program ({ours_file.name}) ---", numbered(ours_text),
            f"--- LinuxCNC program ({lcnc_file.name}) ---", numbered(lcnc_text)])
        return result

    # rs274 reads the program, then waits for a line on stdin before it exits (batch mode -g).
    try:
        rs = run([args.rs274, "-g", str(lcnc_file)], stdin="\n",
                 env=rs274_env(workdir / f"home{index}"))
        if rs.returncode != 0:
            raise outputs.OutputError(f"exit code {rs.returncode}: {rs.stderr.strip()}")
        theirs = outputs.parse_rs274(rs.stdout)
    except (outputs.OutputError, OSError, subprocess.TimeoutExpired) as e:
        return fail("rs274 failed on the generated program (a generator bug if rs274 ran)",
                    f"rs274: {e}")
    diff = outputs.first_difference(prog.expected, theirs, outputs.RS274_DECIMALS_TOL)
    if diff:
        return fail("rs274 disagrees with the generator's model (harness bug)",
                    difference_text(diff, [("model", prog.expected), ("rs274", theirs)]))
    if args.no_mcnc:
        return result

    cmd = [args.mcnc, "interp", str(ours_file)]
    try:
        ours_run = run(cmd)
        ours = outputs.parse_ours(ours_run.stdout)
        if ours_run.returncode != 0:
            raise outputs.OutputError(f"exit code {ours_run.returncode}: {ours_run.stderr.strip()}")
    except (outputs.OutputError, OSError, subprocess.TimeoutExpired) as e:
        return fail("mcnc interp failed", f"mcnc interp: {e}\ncommand: {' '.join(cmd)}")
    runs = [("mcnc interp", ours), ("rs274", theirs), ("model", prog.expected)]
    diff = outputs.first_difference(ours, theirs, outputs.RS274_DECIMALS_TOL)
    if diff:
        return fail("mcnc interp differs from rs274", difference_text(diff, runs))
    diff = outputs.first_difference(ours, prog.expected, outputs.TOL)
    if diff:
        return fail("mcnc interp differs by more than 1e-6 from the generator's exact model, which "
                    "agrees with rs274 to rs274's 4 printed decimals of arc centres",
                    difference_text(diff, runs))
    return result


def difference_text(diff, runs) -> str:
    index, field = diff
    lines = [f"first difference: command {index + 1}, {field}"]
    for name, motions in runs:
        before = motions[index - 1] if 0 < index <= len(motions) else None
        here = motions[index] if index < len(motions) else None
        lines.append(f"  {name:12} previous: {outputs.describe(before)}")
        lines.append(f"  {name:12} this:     {outputs.describe(here)}")
    return "\n".join(lines)


def parse_args():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--mcnc", default="build/bin/mcnc", help="the mcnc executable")
    p.add_argument("--rs274", default=shutil.which("rs274") or "/usr/bin/rs274")
    p.add_argument("--seed", default=DEFAULT_SEED, help="any string; programs are seed/index")
    p.add_argument("--count", type=int, default=300, help="number of programs")
    p.add_argument("--only", type=int, help="run only this program index")
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    p.add_argument("--keep", help="write the programs to this directory and keep them")
    p.add_argument("--no-mcnc", action="store_true",
                   help="harness self-check: compare the generator's model with rs274 only")
    return p.parse_args()


def main() -> int:
    args = parse_args()
    if not (os.path.isfile(args.rs274) and os.access(args.rs274, os.X_OK)):
        print(f"rs274 not found ({args.rs274}): install linuxcnc-uspace (scripts/install-deps)")
        return 1
    if not args.no_mcnc and not os.access(args.mcnc, os.X_OK):
        print(f"mcnc not found: {args.mcnc}")
        return 1
    indices = [args.only] if args.only is not None else list(range(args.count))
    started = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="interp_vs_rs274.") as tmp:
        workdir = Path(args.keep or tmp)
        workdir.mkdir(parents=True, exist_ok=True)
        with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
            results = list(pool.map(lambda i: check_program(i, args, workdir), indices))
    failures = [r for r in results if r.failure]
    stats = sum((r.stats for r in results), collections.Counter())
    commands = sum(r.commands for r in results)
    print(f"seed {args.seed}: {len(results)} programs, {commands} commands, "
          f"{len(failures)} failing, {time.monotonic() - started:.1f} s")
    print("exercised: " + ", ".join(f"{k} {v}" for k, v in sorted(stats.items())))
    if failures:
        print(failures[0].failure)
        if len(failures) > 1:
            print("other failing programs: " + " ".join(str(r.index) for r in failures[1:50]))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
