#!/usr/bin/python3
"""Differential test: `mcnc interp --dialect fanuc-mill` against LinuxCNC's rs274 on random
mill programs.

LinuxCNC's native dialect is a mill dialect. Each seeded program mixes rapid and feed moves
(absolute and G91), arcs in the three planes (I/J/K and R, some helical), tool length
compensation (G43/G49 with H), cutter radius compensation (G41/G42 with D around a rectangle)
the drilling cycles G81, G82, G83, G73, G85, G89 with R, Q, P, G98/G99 and, in G91, L
repeats, and G92 or G52 coordinate settings. Both interpreters run it; their motions (rapid, feed and arc end points in machine
coordinates, arc centres and directions, feeds, dwells) must agree command by command within
1e-4 mm (rs274 prints 4 decimals).

Intentional differences, kept out of the programs or out of the comparison:
- rs274 reads G21/G94 (our mill's table, seed 003, has neither: ours starts metric, per minute)
  and prints positions without the tool length offset, which it reports separately
  (USE_TOOL_LENGTH_OFFSET); the comparison adds it back. Its tool table is in inches: T1 Z1
  D0.5 is our H1/D1 of 25.4 mm and radius 6.35 mm.
- rs274 takes P only in its dwelling cycles (G82, G86, G88, G89; ours keeps a P of any cycle
  for the next), in seconds (ours ms, FANUC), and L as the repeat count (ours K or L). G76 and
  G87 are LinuxCNC's threading and back boring with other words, G84/G74 its
  spindle-synchronised tapping: not generated.
- G83's clearance above the last depth and G73's back-off are rs274's fixed 0.010 inch
  (0.254 mm); ours are parameters (`cycles.drill_clearance`, `cycles.drill_retract`), set to
  that here.
- G85/G89 with G98: rs274 feeds out all the way to the initial level, FANUC (ours) feeds out
  to R and goes on at rapid: generated with G99 only.
- rs274 takes each block's own starting Z as the G98 level; ours keeps the level where the
  cycle began (FANUC). Every cycle here starts with G98 or G99 and keeps it until G80.
- The cutter compensation's entry move: rs274 ends it where its own offset line meets the next
  element's, FANUC (ours) at the next element's offset start. The two agree when the entry
  runs along the first side, as generated.
- rs274 keeps G92 and G52 in one offset (a G52 replaces a G92's, G52 X0 Y0 Z0 clears both),
  FANUC two (G92 shifts the work systems, G52 is local to them): a program uses one of them,
  and G92 only without G43 (rs274 counts the tool length in the current point).
- Moves that do not move (ours positions the hole even when already above it) are dropped on
  both sides before comparing.

    mill_vs_rs274.py --mcnc build/bin/mcnc [--seed S] [--count N] [--only I] [--keep DIR]

Exit code 0 when every program agrees, 1 otherwise (rs274 missing included).
"""
from __future__ import annotations

import argparse
import collections
import concurrent.futures
import json
import math
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, str(Path(__file__).resolve().parent))

from interp_vs_rs274 import numbered, rs274_env, run  # noqa: E402

DEFAULT_SEED = "mill-1"
TOL = 1e-4 + 1e-9
CANON_CALL = re.compile(r"^\s*\d+\s+N\S*\s+([A-Z_0-9]+)\((.*)\)\s*$")
RS274_TOOLS = "T1 P1 Z1 D0.5 ;\nT2 P2 Z2 D0.25 ;\n"
OUR_PARAMS = """dialect: fanuc-mill
tool_geometry: {1: {Z: 25.4, R: 6.35}, 2: {Z: 50.8, R: 3.175}}
cycles: {drill_clearance: 0.254, drill_retract: 0.254}
"""
# The plane's axes (first, second) and its normal, and how rs274 orders ARC_FEED's words.
PLANES = {
    "G17": (("X", "Y"), "Z", "CANON_PLANE_XY", ("X", "Y")),
    "G18": (("Z", "X"), "Y", "CANON_PLANE_XZ", ("Z", "X")),
    "G19": (("Y", "Z"), "X", "CANON_PLANE_YZ", ("Y", "Z")),
}
CENTRE_WORDS = {"X": "I", "Y": "J", "Z": "K"}


@dataclass
class Motion:
    op: str
    to: dict
    centre: dict = field(default_factory=dict)
    direction: str = ""
    feed: float = 0.0
    seconds: float = 0.0
    origin: str = ""


def fmt(v: float) -> str:
    return f"{v:.3f}"


class Generator:
    """One program in both spellings; tracks the programmed position (absolute, mm)."""

    def __init__(self, seed: str):
        self.rnd = random.Random(seed)
        self.pos = {"X": 0.0, "Y": 0.0, "Z": 50.0}
        self.blocks: list[tuple[str, str]] = []  # ours, LinuxCNC's
        self.length_on = False  # G43 in force
        self.offset_code = ""  # "G92" or "G52" once one is used (a program uses only one)
        self.local = {"X": 0.0, "Y": 0.0, "Z": 0.0}  # the G52 shift in force

    def r(self, lo: float, hi: float) -> float:
        return round(self.rnd.uniform(lo, hi), 3)

    def block(self, text: str, lcnc: str | None = None):
        self.blocks.append((text, text if lcnc is None else lcnc))

    def moves(self):
        for _ in range(self.rnd.randint(1, 3)):
            code = self.rnd.choice(["G0", "G1"])
            target = {a: self.r(-40, 40) for a in "XY"}
            target["Z"] = self.r(5, 40)
            axes = self.rnd.sample("XYZ", self.rnd.randint(1, 3))
            feed = f" F{self.rnd.randint(50, 2000)}" if code == "G1" else ""
            if self.rnd.random() < 0.3:
                words = " ".join(f"{a}{fmt(target[a] - self.pos[a])}" for a in sorted(axes))
                self.block(f"G91 {code} {words}{feed}")
                self.block("G90")
            else:
                self.block(f"{code} " + " ".join(f"{a}{fmt(target[a])}" for a in sorted(axes)) +
                           feed)
            for a in axes:
                self.pos[a] = target[a]

    def arc(self):
        plane = self.rnd.choice(list(PLANES))
        (a, b), normal, _, _ = PLANES[plane]
        radius = self.r(5, 25)
        start_angle = self.rnd.uniform(0, 2 * math.pi)
        centre = (self.pos[a] - radius * math.cos(start_angle),
                  self.pos[b] - radius * math.sin(start_angle))
        sweep = self.rnd.uniform(0.3, 2 * math.pi - 0.3)
        end = (round(centre[0] + radius * math.cos(start_angle + sweep), 3),
               round(centre[1] + radius * math.sin(start_angle + sweep), 3))
        code = self.rnd.choice(["G2", "G3"])
        words = f"{a}{fmt(end[0])} {b}{fmt(end[1])}"
        if self.rnd.random() < 0.3:
            self.pos[normal] = self.r(5, 40)  # helical
            words += f" {normal}{fmt(self.pos[normal])}"
        if self.rnd.random() < 0.3:
            # R: the shorter arc for R > 0, the longer for R < 0, of the chord's circle.
            chord = math.hypot(end[0] - self.pos[a], end[1] - self.pos[b])
            r = max(radius, chord / 2 + 0.5)
            sign = self.rnd.choice([1, -1])
            words += f" R{fmt(sign * r)}"
        else:
            words += (f" {CENTRE_WORDS[a]}{fmt(centre[0] - self.pos[a])}"
                      f" {CENTRE_WORDS[b]}{fmt(centre[1] - self.pos[b])}")
        self.block(f"{plane} {code} {words} F{self.rnd.randint(50, 1000)}")
        self.pos[a], self.pos[b] = end
        self.block("G17")

    def length(self):
        h = self.rnd.choice([1, 2])
        code = self.rnd.choice(["G43", "G43", "G49"])
        z = self.r(10, 40)
        # A motion code in the block: after G80 rs274 has none in force (FANUC keeps G00/G01).
        words = f"{code} H{h} G0 Z{fmt(z)}" if code == "G43" else f"G49 G0 Z{fmt(z)}"
        self.block(words)
        self.pos["Z"] = z
        self.length_on = code == "G43"

    def coordinates(self):
        # rs274 keeps G92 and G52 in one offset (G52 replaces a G92's, G52 X0 clears both);
        # FANUC keeps them apart: a program uses one of them. rs274's G92 under G43 counts the
        # tool length differently: only without it.
        if self.length_on:
            return
        self.offset_code = self.offset_code or self.rnd.choice(["G92", "G52"])
        value = {a: self.r(-20, 20) for a in "XYZ"}
        if self.rnd.random() < 0.2:
            value = {a: 0.0 for a in "XYZ"}
        self.block(f"{self.offset_code} " + " ".join(f"{a}{fmt(value[a])}" for a in "XYZ"))
        for a in "XYZ":
            if self.offset_code == "G92":
                self.pos[a] = value[a]  # the current point reads the values
            else:
                self.pos[a] = round(self.pos[a] + self.local[a] - value[a], 3)
                self.local[a] = value[a]

    def cycle(self):
        if self.pos["Z"] < 10:
            self.block("G0 Z20.")
            self.pos["Z"] = 20.0
        code = self.rnd.choice(["G81", "G82", "G83", "G73", "G85", "G89"])
        r_level = self.r(-2, self.pos["Z"] - 2)
        bottom = self.r(r_level - 20, r_level - 1)
        # rs274's G85/G89 feed out to the G98 level; FANUC's feed to R, then rapid (below).
        ret = "G99" if code in ("G85", "G89") else self.rnd.choice(["G98", "G99"])
        words = ""
        if code in ("G83", "G73"):
            words += f" Q{fmt(self.r(0.8, 6))}"
        dwell = ("", "")
        if code in ("G82", "G89"):
            ms = self.rnd.choice([100, 250, 1000])  # ours: ms (FANUC); rs274: seconds
            dwell = (f" P{ms}", f" P{ms / 1000}")
        feed = f" F{self.rnd.randint(50, 500)}"
        if self.rnd.random() < 0.35:
            # G91: R from the initial level, Z from R, L holes each moved by X Y.
            dx, dy = self.r(-15, 15), self.r(-15, 15)
            count = self.rnd.randint(1, 3)
            head = (f"G91 {ret} {code} X{fmt(dx)} Y{fmt(dy)} Z{fmt(bottom - r_level)} "
                    f"R{fmt(r_level - self.pos['Z'])}{words}")
            self.block(f"{head}{dwell[0]} L{count}{feed}", f"{head}{dwell[1]} L{count}{feed}")
            self.block("G90 G80")
            self.pos["X"] += count * dx
            self.pos["Y"] += count * dy
        else:
            x, y = self.r(-40, 40), self.r(-40, 40)
            head = f"{ret} {code} X{fmt(x)} Y{fmt(y)} Z{fmt(bottom)} R{fmt(r_level)}{words}"
            self.block(f"{head}{dwell[0]}{feed}", f"{head}{dwell[1]}{feed}")
            for _ in range(self.rnd.randint(0, 2)):
                x, y = self.r(-40, 40), self.r(-40, 40)
                self.block(f"X{fmt(x)} Y{fmt(y)}")
            self.block("G80")
            self.pos["X"], self.pos["Y"] = x, y
        self.pos["Z"] = self.pos["Z"] if ret == "G98" else r_level

    def compensation(self):
        # A rectangle around (cx, cy), entered along its first side (where rs274's entry and
        # FANUC's agree) to its lower left corner. The exit goes to a point outside it.
        cx, cy = self.r(-20, 20), self.r(-20, 20)
        w, h = self.r(15, 40), self.r(15, 40)
        side = self.rnd.choice(["G41", "G42"])
        d = self.rnd.choice([1, 2])
        x0, y0 = cx - w / 2, cy - h / 2
        # Clockwise (up first) or counter-clockwise (right first): G41 clockwise and G42
        # counter-clockwise cut outside (arcs at the corners), the others inside.
        clockwise = self.rnd.random() < 0.5
        corners = [(x0, y0 + h), (x0 + w, y0 + h), (x0 + w, y0), (x0, y0)]
        if not clockwise:
            corners = [(x0 + w, y0), (x0 + w, y0 + h), (x0, y0 + h), (x0, y0)]
        start = (x0, y0 - 20) if clockwise else (x0 - 20, y0)
        self.block(f"G0 X{fmt(start[0])} Y{fmt(start[1])}")
        self.block(f"{side} D{d} G1 X{fmt(x0)} Y{fmt(y0)} F{self.rnd.randint(100, 800)}")
        for x, y in corners:
            self.block(f"X{fmt(x)} Y{fmt(y)}")
        self.block(f"G40 G0 X{fmt(x0 - 20)} Y{fmt(y0 - 20)}")
        self.pos["X"], self.pos["Y"] = round(x0 - 20, 3), round(y0 - 20, 3)

    def program(self) -> tuple[str, str]:
        self.block("G0 X0 Y0 Z50.")
        steps = [self.moves, self.arc, self.arc, self.length, self.cycle, self.cycle,
                 self.compensation, self.coordinates]
        for _ in range(self.rnd.randint(4, 9)):
            self.rnd.choice(steps)()
        ours = "\n".join(b[0] for b in self.blocks)
        lcnc = "\n".join(b[1] for b in self.blocks)
        ours = "G17 G90 G40 G49 G80 G54 S1000 M03\n" + ours + "\nM30\n"
        lcnc = "G21 G17 G90 G94 G40 G49 G80 G54 G92.1 S1000 M03\n" + lcnc + "\nM2\n"
        return ours, lcnc


def floats(args: str):
    return [float(a) for a in args.replace(" ", ",").split(",") if a]


def parse_rs274(stdout: str) -> list[Motion]:
    motions: list[Motion] = []
    feed, plane, tool_z = 0.0, "CANON_PLANE_XY", 0.0
    shift = {"X": 0.0, "Y": 0.0, "Z": 0.0}  # rs274 prints program positions: G92/G52 added
    for line in stdout.splitlines():
        call = CANON_CALL.match(line)
        if not call:
            continue
        name, args = call.groups()
        origin = line.strip()
        if name == "SET_FEED_RATE":
            feed = float(args)
        elif name == "SELECT_PLANE":
            plane = args.strip()
        elif name == "USE_TOOL_LENGTH_OFFSET":
            tool_z = floats(args)[2]
        elif name == "SET_G92_OFFSET":
            shift = dict(zip("XYZ", floats(args)[:3]))
        elif name == "SET_G5X_OFFSET" and any(floats(args)[1:4]):
            raise RuntimeError(f"a work offset the test does not set: {origin}")
        elif name in ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED"):
            v = floats(args)
            to = {"X": v[0] + shift["X"], "Y": v[1] + shift["Y"], "Z": v[2] + tool_z + shift["Z"]}
            motions.append(Motion("rapid" if name == "STRAIGHT_TRAVERSE" else "linear", to,
                                  feed=feed if name == "STRAIGHT_FEED" else 0.0, origin=origin))
        elif name == "ARC_FEED":
            v = floats(args)
            (first, second), normal = next((p[3], p[1]) for p in PLANES.values() if p[2] == plane)
            to = {first: v[0], second: v[1], normal: v[5]}
            centre = {first: v[2], second: v[3]}
            for d in (to, centre):
                for a in d:
                    d[a] += shift[a] + (tool_z if a == "Z" else 0.0)
            motions.append(Motion("arc", to, centre, "cw" if v[4] < 0 else "ccw", feed,
                                  origin=origin))
        elif name == "DWELL":
            motions.append(Motion("dwell", {}, seconds=float(args), origin=origin))
    return motions


def parse_ours(stdout: str) -> list[Motion]:
    motions: list[Motion] = []
    for line in stdout.splitlines():
        c = json.loads(line)
        if c["op"] == "alarm":
            raise RuntimeError(f"alarm {c['number']} line {c['line']}: {c['text']}")
        if c["op"] in ("rapid", "linear", "arc"):
            motions.append(Motion(c["op"], c["to"], c.get("center", {}), c.get("dir", ""),
                                  c.get("feed", 0.0), origin=line))
        elif c["op"] == "dwell":
            motions.append(Motion("dwell", {}, seconds=c["seconds"], origin=line))
    return motions


def moving(motions: list[Motion]) -> list[Motion]:
    """Leaves out the moves that end where the tool already is."""
    out, at = [], {"X": 0.0, "Y": 0.0, "Z": 0.0}
    for m in motions:
        if m.op != "dwell" and all(abs(m.to[a] - at[a]) <= TOL for a in at):
            continue
        if m.op != "dwell":
            at = dict(m.to)
        out.append(m)
    return out


def difference(a: Motion, b: Motion) -> str:
    if a.op != b.op:
        return f"op {a.op} / {b.op}"
    for k in a.to:
        if abs(a.to[k] - b.to.get(k, math.inf)) > TOL:
            return f"end {k}"
    for k in a.centre:
        if abs(a.centre[k] - b.centre.get(k, math.inf)) > TOL:
            return f"centre {k}"
    if a.direction != b.direction:
        return "direction"
    if abs(a.feed - b.feed) > TOL or abs(a.seconds - b.seconds) > 1e-9:
        return "feed or dwell"
    return ""


def check_program(index: int, args, workdir: Path) -> tuple[str, collections.Counter]:
    ours_text, lcnc_text = Generator(f"{args.seed}/{index}").program()
    ours_file, lcnc_file = workdir / f"p{index}.nc", workdir / f"p{index}.ngc"
    params, tools = workdir / "mill.yaml", workdir / "tools.tbl"
    ours_file.write_text(ours_text)
    lcnc_file.write_text(lcnc_text)
    stats = collections.Counter()
    for text in ours_text.splitlines():
        for word in re.findall(r"G\d+", text):
            stats[word] += 1

    def fail(headline: str, detail: str) -> tuple[str, collections.Counter]:
        return "\n".join([
            f"FAIL seed={args.seed} program={index}: {headline}", detail,
            f"reproduce: /usr/bin/python3 {Path(__file__).resolve()} --mcnc {args.mcnc} "
            f"--seed {args.seed} --only {index} --keep /tmp/mill_vs_rs274",
            "--- program ---", numbered(lcnc_text)]), stats

    try:
        rs = run([args.rs274, "-g", str(lcnc_file), "-t", str(tools)], stdin="\n",
                 env=rs274_env(workdir / f"home{index}"))
        theirs = moving(parse_rs274(rs.stdout))
        if rs.returncode != 0 or "PROGRAM_END()" not in rs.stdout:
            return fail("rs274 refused the generated program (a generator bug)",
                        "\n".join(line for line in rs.stdout.splitlines()
                                  if not CANON_CALL.match(line)) + rs.stderr)
        ours_run = run([args.mcnc, "interp", "--param", str(params), str(ours_file)])
        ours = moving(parse_ours(ours_run.stdout))
    except (RuntimeError, OSError, subprocess.TimeoutExpired, json.JSONDecodeError) as e:
        return fail("an interpreter failed", str(e))
    for i in range(max(len(ours), len(theirs))):
        a = ours[i] if i < len(ours) else None
        b = theirs[i] if i < len(theirs) else None
        why = "missing" if a is None or b is None else difference(a, b)
        if why:
            return fail(f"motion {i + 1} differs: {why}",
                        f"  mcnc:  {a.origin if a else '-'}\n  rs274: {b.origin if b else '-'}")
    stats["motions"] += len(ours)
    for m in ours:
        stats[m.op] += 1
    return "", stats


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--mcnc", default="build/bin/mcnc")
    p.add_argument("--rs274", default=shutil.which("rs274") or "/usr/bin/rs274")
    p.add_argument("--seed", default=DEFAULT_SEED)
    p.add_argument("--count", type=int, default=80)
    p.add_argument("--only", type=int)
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    p.add_argument("--keep")
    args = p.parse_args()
    if not (os.path.isfile(args.rs274) and os.access(args.rs274, os.X_OK)):
        print(f"rs274 not found ({args.rs274}): install linuxcnc-uspace (scripts/install-deps)")
        return 1
    indices = [args.only] if args.only is not None else list(range(args.count))
    started = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="mill_vs_rs274.") as tmp:
        workdir = Path(args.keep or tmp)
        workdir.mkdir(parents=True, exist_ok=True)
        (workdir / "mill.yaml").write_text(OUR_PARAMS)
        (workdir / "tools.tbl").write_text(RS274_TOOLS)
        with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
            results = list(pool.map(lambda i: check_program(i, args, workdir), indices))
    failures = [f for f, _ in results if f]
    stats = sum((s for _, s in results), collections.Counter())
    print(f"seed {args.seed}: {len(indices)} programs, {len(failures)} failing, "
          f"{time.monotonic() - started:.1f} s")
    print("exercised: " + ", ".join(f"{k} {v}" for k, v in sorted(stats.items())))
    if failures:
        print(failures[0])
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
