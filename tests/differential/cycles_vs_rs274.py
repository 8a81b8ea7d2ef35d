#!/usr/bin/python3
"""Differential test: G71/G72 stock removal and G70 finishing of `mcnc interp` against LinuxCNC's
rs274.

Seeded random type I contours (G71: Z falling, X rising; G72 on every other program: the same
contour with the axes swapped; lines, tapers and arcs) are written as a FANUC-style program for
mcnc (G71 U R / G71 P Q U0 W0 F, G72 W R / G72 P Q U0 W0 F, then G70 P Q) and as a LinuxCNC
program (the contour in an O-sub, `G71 Q X Z D0 I R` / `G72 ...`, `G70 Q X Z D0 P1`; LinuxCNC: D = stock to leave,
I = depth of cut, R = retract, found by experiment with rs274 2.9.0~pre1). Compared:

  1. the roughing pass depths: every level mcnc cuts (start X minus k times the depth, above the
     contour's first point B) is a level rs274 cuts, with the same end of the cut (Z on the
     contour) within rs274's 4 decimals; and every rs274 level on that grid is one mcnc cuts;
  2. the finishing pass: the end points of G70's moves, in order.

Intentional differences (not compared):
  - rs274 also cuts at the start level itself (a pass of depth 0) and adds a pass between the last
    full depth and the contour; mcnc (FANUC, gsk D2-24) cuts full depths only and then goes to B'
    and along the contour.
  - rs274's retract and return moves (it rapids out along X before returning in Z; mcnc retracts
    at 45 degrees by R at feed, gsk A.6.30 step 4) and its approach to the contour.
  - rs274 runs the semi-finishing pass as part of its G71 with a different start; mcnc's is the
    contour moved by the allowance, compared through G70 here (allowance 0).

    cycles_vs_rs274.py --mcnc build/bin/mcnc [--seed S] [--count N] [--keep DIR]

Exit code 0 when every program agrees, 1 otherwise (rs274 missing included).
"""
from __future__ import annotations

import argparse
import math
import random
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

sys.dont_write_bytecode = True
sys.path.insert(0, str(Path(__file__).resolve().parent))

import outputs  # noqa: E402

DEFAULT_SEED = "mcnc-g71"
COUNTS = {"levels": 0, "rs274 levels": 0, "finishing points": 0}
TOL = 2e-4  # rs274 prints 4 decimals


def arc_is_monotonic(p, q, centre, cw):
    """Whether the arc from p to q (z, x) about centre stays monotonic in z and x."""
    a0 = math.atan2(p[1] - centre[1], p[0] - centre[0])
    a1 = math.atan2(q[1] - centre[1], q[0] - centre[0])
    sweep = a1 - a0
    if cw:
        while sweep > 0:
            sweep -= 2 * math.pi
    else:
        while sweep < 0:
            sweep += 2 * math.pi
    for k in range(-8, 9):
        axis = k * math.pi / 2
        t = (axis - a0) / sweep if sweep else -1
        if 1e-6 < t < 1 - 1e-6:
            return False
    return True


def contour(rng):
    """(start radius, start z, [(kind, z, x radius, r, cw)]) of a type I OD contour."""
    z, x = 2.0, round(rng.uniform(3, 15), 3)
    first_x = x
    elements = []
    for _ in range(rng.randint(2, 7)):
        nz = round(z - rng.uniform(2, 12), 3)
        nx = round(x + (0.0 if rng.random() < 0.3 else rng.uniform(0.5, 6)), 3)
        if nx != x and rng.random() < 0.35:
            chord = math.hypot(nz - z, nx - x)
            r = round(chord * rng.uniform(0.8, 3.0), 3)
            cw = rng.random() < 0.5
            h = math.sqrt(max(r * r - chord * chord / 4, 0))
            mz, mx = (z + nz) / 2, (x + nx) / 2
            dz, dx = (nz - z) / chord, (nx - x) / chord
            side = -1 if cw else 1  # the centre of the short arc: left of the chord for CCW
            centre = (mz - side * h * dx, mx + side * h * dz)
            if arc_is_monotonic((z, x), (nz, nx), centre, cw):
                elements.append(("arc", nz, nx, r, cw))
                z, x = nz, nx
                continue
        elements.append(("line", nz, nx, 0.0, False))
        z, x = nz, nx
    top = round(x + rng.uniform(1, 8), 3)
    return top, 2.0, first_x, elements


def fmt(v):
    return f"{v:.3f}"


def programs(g72, top, zs, first_x, elements, depth, retract):
    """The two programs. G72 takes the G71 contour with its axes swapped: c (the G71 Z) becomes
    X + 80 (radius) and s (the G71 X radius) becomes Z - 60, so its passes run along X and step
    in Z; the swap mirrors the arcs' direction."""
    def at(c, s):  # (X radius, Z) of a contour point
        return (c + 80.0, s - 60.0) if g72 else (s, c)

    code, depth_word = ("G72", "W") if g72 else ("G71", "U")
    ax, az = at(zs, top)
    bx, bz = at(zs, first_x)
    first = f"Z{fmt(bz)}" if g72 else f"X{fmt(2 * bx)}"
    ours = [f"G00 X{fmt(2 * ax)} Z{fmt(az)}", f"{code} {depth_word}{fmt(depth)} R{fmt(retract)}",
            f"{code} P10 Q20 U0 W0 F100", f"N10 G00 {first}"]
    sub = [f"G0 X{fmt(2 * bx)} Z{fmt(bz)}"]
    for i, (kind, c, s, r, cw) in enumerate(elements):
        x, z = at(c, s)
        n = "N20 " if i == len(elements) - 1 else ""
        if kind == "line":
            ours.append(f"{n}G01 X{fmt(2 * x)} Z{fmt(z)}")
            sub.append(f"G1 X{fmt(2 * x)} Z{fmt(z)}")
        else:
            g = "G02" if cw != g72 else "G03"
            ours.append(f"{n}{g} X{fmt(2 * x)} Z{fmt(z)} R{fmt(r)}")
            sub.append(f"{g[0]}{g[2]} X{fmt(2 * x)} Z{fmt(z)} R{fmt(r)}")
    ours += ["G70 P10 Q20", "M30"]
    theirs = ["G18 G21 G7 F100", "O100 SUB"] + sub + ["O100 ENDSUB",
              f"G0 X{fmt(2 * ax)} Z{fmt(az)}",
              f"{code} Q100 X{fmt(2 * ax)} Z{fmt(az)} D0 I{fmt(depth)} R{fmt(retract)}",
              "(DEBUG,G70)", f"G70 Q100 X{fmt(2 * ax)} Z{fmt(az)} D0 P1", "M2"]
    return "\n".join(ours) + "\n", "\n".join(theirs) + "\n", (ax, az), at


def parse_rs274(stdout):
    """Moves (op, x, z) of rs274's G71 and of its G70, split at the DEBUG message."""
    parts = [[], []]
    k = 0
    for line in stdout.splitlines():
        call = outputs.CANON_CALL.match(line)
        if not call:
            if "error" in line.lower():
                raise outputs.OutputError(line.strip())
            continue
        name, args = call.groups()
        if name == "MESSAGE" and "G70" in args:
            k = 1
        elif name in ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED"):
            v = outputs.floats(args)
            parts[k].append(("rapid" if name == "STRAIGHT_TRAVERSE" else "linear", v[0], v[2]))
        elif name == "ARC_FEED":
            v = outputs.floats(args)
            parts[k].append(("arc", v[1], v[0]))
    return parts


def roughing_cuts(moves, start, g72):
    """(level, end) of the roughing cuts: feeds from the start's Z towards -Z at a constant X
    (G71), or from the start's X towards -X at a constant Z (G72)."""
    cuts = []
    prev = start
    for op, x, z in moves:
        level, end, prev_level, prev_end, begin = ((z, x, prev[1], prev[0], start[0]) if g72
                                                   else (x, z, prev[0], prev[1], start[1]))
        if (op == "linear" and abs(level - prev_level) < 1e-9 and end < prev_end - 1e-6
                and abs(prev_end - begin) < TOL):
            cuts.append((level, end))
        prev = (x, z)
    return cuts


def finishing_points(moves):
    pts = []
    for op, x, z in moves:
        if op in ("linear", "arc") and (not pts or math.hypot(x - pts[-1][0], z - pts[-1][1]) > TOL):
            pts.append((x, z))
    return pts


def compare(mcnc, rs274, index, rng, keep):
    g72 = index % 2 == 1
    top, zs, first_x, elements = contour(rng)
    depth = round(rng.uniform(0.3, 2.5), 3)
    retract = round(rng.uniform(0.2, 1.0), 3)
    ours_text, theirs_text, start, at = programs(g72, top, zs, first_x, elements, depth, retract)
    with tempfile.TemporaryDirectory() as d:
        ours_file, theirs_file = Path(d, "p.nc"), Path(d, "p.ngc")
        ours_file.write_text(ours_text)
        theirs_file.write_text(theirs_text)
        if keep:
            shutil.copy(ours_file, Path(keep, f"{index}.nc"))
            shutil.copy(theirs_file, Path(keep, f"{index}.ngc"))
        a = subprocess.run([mcnc, "interp", str(ours_file)], capture_output=True, text=True,
                           timeout=30)
        b = subprocess.run([rs274, "-g", str(theirs_file)], capture_output=True, text=True,
                           timeout=30, cwd=d)
    try:
        ours = outputs.parse_ours(a.stdout)
        cycle, g70 = parse_rs274(b.stdout)
    except outputs.OutputError as e:
        return f"program {index}: {e}\n{ours_text}\n{theirs_text}"
    cycle_line = 3
    our_cycle = [(m.op, m.x, m.z) for m in ours if f"line {cycle_line}:" in m.origin]
    our_g70 = [(m.op, m.x, m.z) for m in ours
               if f"line {cycle_line}:" not in m.origin and m.op in ("linear", "arc")]
    mine = roughing_cuts(our_cycle, start, g72)
    theirs = roughing_cuts(cycle, start, g72)
    # The levels on the grid of full depths from the start, short of the contour's first point.
    first_level = at(zs, first_x)[1 if g72 else 0]
    top_level = start[1 if g72 else 0]

    def on_grid(level):
        k = (top_level - level) / depth
        return abs(k - round(k)) < 1e-3 and round(k) >= 1

    levels = [(lv, e) for lv, e in theirs if on_grid(lv) and lv > first_level + 1e-6]
    problems = []
    fa = finishing_points(our_g70)
    if not mine or len(fa) < 2:
        problems.append("nothing to compare: no roughing level or no finishing pass")
    COUNTS["levels"] += len(mine)
    COUNTS["rs274 levels"] += len(levels)
    COUNTS["finishing points"] += len(fa)
    name = "Z" if g72 else "X (radius)"
    for lv, e in mine:
        match = [t for t in theirs if abs(t[0] - lv) < TOL]
        if not match:
            problems.append(f"level {name} {lv:.4f} cut by mcnc, not by rs274")
        elif abs(match[0][1] - e) > TOL:
            problems.append(f"level {name} {lv:.4f}: mcnc cuts to {e:.4f}, rs274 to {match[0][1]:.4f}")
    for lv, _ in levels:
        if not any(abs(m[0] - lv) < TOL for m in mine):
            problems.append(f"level {name} {lv:.4f} cut by rs274, not by mcnc")
    fb = finishing_points(g70)
    if len(fa) != len(fb) or any(math.hypot(p[0] - q[0], p[1] - q[1]) > TOL for p, q in zip(fa, fb)):
        problems.append(f"finishing pass differs:\n  mcnc  {fa}\n  rs274 {fb}")
    if problems:
        return f"program {index} ({'G72' if g72 else 'G71'}):\n  " + "\n  ".join(problems) + \
            f"\n{ours_text}\n{theirs_text}"
    return None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--mcnc", required=True)
    ap.add_argument("--seed", default=DEFAULT_SEED)
    ap.add_argument("--count", type=int, default=60)
    ap.add_argument("--keep")
    args = ap.parse_args()
    rs274 = shutil.which("rs274")
    if rs274 is None:
        print("rs274 not found: install linuxcnc-uspace (scripts/install-deps)")
        return 1
    rng = random.Random(args.seed)
    failures = 0
    for i in range(args.count):
        problem = compare(args.mcnc, rs274, i, rng, args.keep)
        if problem:
            failures += 1
            print(problem)
            if failures >= 3:
                break
    print(f"cycles_vs_rs274: {args.count} programs, seed {args.seed}, {failures} failing; compared "
          + ", ".join(f"{v} {k}" for k, v in COUNTS.items()))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
