#!/usr/bin/python3
"""Conformance (golden) tests of `mcnc interp`.

Each directory below tests/conformance/ is one case:
  program.nc      the program (its first program is the main program; others are found by number)
  params.yaml     optional: passed as --param
  args            optional: extra command-line words (e.g. `--system B`, `--channel 2`)
  progdir/        optional: passed as --progdir
  expected.jsonl  the exact expected output, one JSON object per line

The output is compared line by line as JSON objects; numbers are equal within 1e-6. An alarm line
is compared on op, number and line, plus text, file and col when expected.jsonl gives them.

Usage: run_conformance.py --mcnc build/bin/mcnc [CASE_DIR ...]
With no case directory every case is run. Exits 1 if any case fails.
"""
import argparse
import json
import os
import shlex
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TOL = 1e-6


def equal(a, b):
    if isinstance(a, bool) or isinstance(b, bool):
        return a is b
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return abs(a - b) <= TOL
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(equal(a[k], b[k]) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(equal(x, y) for x, y in zip(a, b))
    return a == b


def differences(exp, act, path=""):
    """Readable list of the fields that differ between two JSON values."""
    out = []
    if isinstance(exp, dict) and isinstance(act, dict):
        for k in sorted(set(exp) | set(act)):
            p = f"{path}.{k}" if path else k
            if k not in act:
                out.append(f"{p}: missing (expected {json.dumps(exp[k])})")
            elif k not in exp:
                out.append(f"{p}: unexpected {json.dumps(act[k])}")
            else:
                out += differences(exp[k], act[k], p)
    elif not equal(exp, act):
        out.append(f"{path}: expected {json.dumps(exp)}, got {json.dumps(act)}")
    return out


def load_lines(text, what):
    rows = []
    for i, line in enumerate(text.splitlines(), 1):
        if not line.strip():
            continue
        try:
            rows.append(json.loads(line))
        except json.JSONDecodeError as e:
            rows.append({"<unparsable>": line, "<error>": f"{what} line {i}: {e}"})
    return rows


def run_case(mcnc, case):
    cmd = [mcnc, "interp"]
    if os.path.exists(os.path.join(case, "params.yaml")):
        cmd += ["--param", os.path.join(case, "params.yaml")]
    if os.path.isdir(os.path.join(case, "progdir")):
        cmd += ["--progdir", os.path.join(case, "progdir")]
    args_file = os.path.join(case, "args")
    if os.path.exists(args_file):
        with open(args_file) as f:
            cmd += shlex.split(f.read(), comments=True)
    cmd.append(os.path.join(case, "program.nc"))
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=60, cwd=case)
    except subprocess.TimeoutExpired:
        return False, ["timeout after 60 s: " + " ".join(cmd)]
    with open(os.path.join(case, "expected.jsonl")) as f:
        expected = load_lines(f.read(), "expected")
    actual = load_lines(proc.stdout, "actual")
    report = []
    n = max(len(expected), len(actual))
    for i in range(n):
        e = expected[i] if i < len(expected) else None
        a = actual[i] if i < len(actual) else None
        if e is None:
            report.append(f"  line {i + 1}: unexpected extra output {json.dumps(a)}")
            continue
        if a is None:
            report.append(f"  line {i + 1}: missing, expected {json.dumps(e)}")
            continue
        if e.get("op") == "alarm" and a.get("op") == "alarm":
            # An alarm's text (and file, col) is compared only when the case gives it.
            a = {k: v for k, v in a.items() if k in e or k in ("op", "number", "line")}
        if not equal(e, a):
            report.append(f"  line {i + 1}:")
            report.append(f"    expected {json.dumps(e)}")
            report.append(f"    actual   {json.dumps(a)}")
            for d in differences(e, a):
                report.append(f"      {d}")
    want_rc = 1 if expected and expected[-1].get("op") == "alarm" else 0
    if proc.returncode != want_rc:
        report.append(f"  exit code {proc.returncode}, expected {want_rc}")
        if proc.stderr.strip():
            report.append("  stderr: " + proc.stderr.strip().replace("\n", "\n          "))
    if len(report) > 40:
        report = report[:40] + [f"  ... {len(report) - 40} more report lines"]
    if report:
        report.insert(0, "  command: " + " ".join(shlex.quote(c) for c in cmd))
    return not report, report


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--mcnc", required=True, help="path of the mcnc executable")
    ap.add_argument("cases", nargs="*", help="case directories (default: all)")
    opts = ap.parse_args()
    mcnc = os.path.abspath(opts.mcnc)
    cases = opts.cases or sorted(
        os.path.join(HERE, d) for d in os.listdir(HERE)
        if os.path.isfile(os.path.join(HERE, d, "expected.jsonl")))
    failed = []
    for case in cases:
        case = os.path.abspath(case)
        ok, report = run_case(mcnc, case)
        name = os.path.basename(case)
        print(f"{'PASS' if ok else 'FAIL'} {name}")
        if not ok:
            failed.append(name)
            print("\n".join(report))
    print(f"{len(cases) - len(failed)}/{len(cases)} cases passed")
    if failed:
        print("failed: " + " ".join(failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
