"""The two interpreters' outputs as one list of `Motion`s (X as radius, Z, mm), and their
comparison.

rs274 (`rs274 -g FILE`) prints canonical calls with 4 decimals, in the program's units (G21: mm)
and with X as the radius even under G7:
    STRAIGHT_TRAVERSE(x, y, z, a, b, c)     STRAIGHT_FEED(x, y, z, a, b, c)
    ARC_FEED(first_end, second_end, first_centre, second_centre, rotation, axis_end, a, b, c)
In the XZ plane (G18) "first" is Z and "second" is X; rotation is -1 for G2 and +1 for G3 (|n| > 1
would add full turns); the > 180° arc of a negative R is told only by its centre. Feed calls
SET_FEED_RATE(f) and SET_FEED_MODE(spindle, 0 per minute | 1 per revolution) come before the move
they apply to. The generated LinuxCNC programs follow each motion with a DEBUG comment printing
the exact end point (#5420 X radius, #5422 Z) with 9 decimals; it arrives as MESSAGE("@ x z")
and replaces the 4-decimal end point. Arc centres stay at 4 decimals.

`mcnc interp` prints one JSON object per line (see the command's contract).
"""
from __future__ import annotations

import json
import re

from progen import Motion

CANON_CALL = re.compile(r"^\s*\d+\s+N\S*\s+([A-Z_0-9]+)\((.*)\)\s*$")
RS274_DECIMALS_TOL = 0.5e-4 + 1e-9   # what rs274's %.4f printing can hide
TOL = 1e-6

FIELDS = {
    "rapid": ("x", "z"),
    "linear": ("x", "z", "feed", "feed_mode"),
    "arc": ("x", "z", "cx", "cz", "dir", "feed", "feed_mode"),
    "dwell": ("seconds",),
}


class OutputError(Exception):
    """The interpreter rejected the program or printed something unexpected."""


def floats(args: str):
    return [float(a) for a in args.split(",")]


def parse_rs274(stdout: str) -> list[Motion]:
    motions: list[Motion] = []
    feed, mode, plane = 0.0, "per_min", ""
    refined = True
    ended = False
    for line in stdout.splitlines():
        call = CANON_CALL.match(line)
        if not call:
            continue
        name, args = call.groups()
        origin = line.strip()
        if name == "MESSAGE" and args.startswith('"@'):
            if refined:
                raise OutputError(f"end-point message without a motion: {origin}")
            x, z = (float(v) for v in args.strip('"@ ').split())
            last = motions[-1]
            if abs(last.x - x) > RS274_DECIMALS_TOL or abs(last.z - z) > RS274_DECIMALS_TOL:
                raise OutputError(f"end-point message does not match the motion: {origin}")
            last.x, last.z, refined = x, z, True
            continue
        if name in ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED", "DWELL") and not refined:
            raise OutputError(f"motion without its end-point message before: {origin}")
        if name == "SET_FEED_RATE":
            feed = float(args)
        elif name == "SET_FEED_MODE":
            mode = "per_rev" if int(floats(args)[1]) else "per_min"
        elif name == "SELECT_PLANE":
            plane = args.strip()
        elif name == "STRAIGHT_TRAVERSE":
            v = floats(args)
            motions.append(Motion("rapid", v[0], v[2], origin=origin))
            refined = False
        elif name == "STRAIGHT_FEED":
            v = floats(args)
            motions.append(Motion("linear", v[0], v[2], feed=feed, feed_mode=mode, origin=origin))
            refined = False
        elif name == "ARC_FEED":
            if plane != "CANON_PLANE_XZ":
                raise OutputError(f"arc outside the XZ plane ({plane}): {origin}")
            v = floats(args)
            if abs(v[4]) != 1:
                raise OutputError(f"arc with full turns: {origin}")
            motions.append(Motion("arc", v[1], v[0], v[3], v[2], "cw" if v[4] < 0 else "ccw",
                                  feed, mode, origin=origin))
            refined = False
        elif name == "DWELL":
            motions.append(Motion("dwell", seconds=float(args), origin=origin))
        elif name == "PROGRAM_END":
            ended = True
            break
    if not refined:
        raise OutputError("last motion without its end-point message")
    if not ended:
        raise OutputError("no PROGRAM_END")
    return motions


def parse_ours(stdout: str) -> list[Motion]:
    """Motions of `mcnc interp`; raises OutputError on an alarm, a bad line or a missing end."""
    motions: list[Motion] = []
    for line in stdout.splitlines():
        if not line.strip():
            continue
        try:
            c = json.loads(line)
        except json.JSONDecodeError as e:
            raise OutputError(f"not JSON ({e}): {line}") from None
        op = c.get("op")
        origin = f"line {c.get('line')}: {line}"
        try:
            if op == "alarm":
                raise OutputError(f"alarm {c.get('number')}: {c.get('text')} "
                                  f"({c.get('file')}:{c.get('line')}:{c.get('col')})")
            if op == "end":
                return motions
            if op == "rapid":
                motions.append(Motion("rapid", c["to"]["X"], c["to"]["Z"], origin=origin))
            elif op == "linear":
                motions.append(Motion("linear", c["to"]["X"], c["to"]["Z"], feed=c["feed"],
                                      feed_mode=c["feed_mode"], origin=origin))
            elif op == "arc":
                turns = c.get("turns", 0)
                name = "arc" if not turns else f"arc with {turns} extra turns"
                if c.get("plane", "ZX") != "ZX":
                    name = f"arc in plane {c['plane']}"
                motions.append(Motion(name, c["to"]["X"], c["to"]["Z"], c["center"]["X"],
                                      c["center"]["Z"], c["dir"], c["feed"], c["feed_mode"],
                                      origin=origin))
            elif op == "dwell":
                name = "dwell in revolutions" if c.get("in_revs") else "dwell"
                motions.append(Motion(name, seconds=c["seconds"], origin=origin))
        except (KeyError, TypeError) as e:
            raise OutputError(f"missing field {e}: {line}") from None
    raise OutputError("no end command")


def describe(m: Motion | None) -> str:
    if m is None:
        return "(nothing)"
    fields = FIELDS.get(m.op, ())
    text = m.op + " " + " ".join(f"{f}={getattr(m, f)!r}" for f in fields)
    return text + (f"   [{m.origin}]" if m.origin else "")


def first_difference(a: list[Motion], b: list[Motion], centre_tol: float):
    """(index, field) of the first command that differs, or None. End points, feeds and dwell
    times must agree within 1e-6; arc centres within centre_tol."""
    for i in range(max(len(a), len(b))):
        if i >= len(a) or i >= len(b):
            return i, "number of commands"
        ma, mb = a[i], b[i]
        if ma.op != mb.op:
            return i, "op"
        for f in FIELDS[ma.op]:
            va, vb = getattr(ma, f), getattr(mb, f)
            tol = centre_tol if f in ("cx", "cz") else TOL
            if isinstance(va, str) or isinstance(vb, str):
                if va != vb:
                    return i, f
            elif not abs(va - vb) <= tol:
                return i, f
    return None
