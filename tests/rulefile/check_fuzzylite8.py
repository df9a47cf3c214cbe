#!/usr/bin/env python3
"""Every .fll of the corpus against fuzzylite 8 (pyfuzzylite 8.0.6): the same outputs to 1e-12.

Usage: check_fuzzylite8.py <venv python> <fuzzypid binary> <corpus dir>
Run by the system python3; the venv's python evaluates fuzzylite (a separate process, so the
test needs nothing from the venv itself). Exit 77 (ctest SKIP_RETURN_CODE) when the venv is
missing or holds another version: scripts/oracle-venv.sh makes it.

Each file is evaluated on a grid over its input ranges widened by 10 % (at most ~400 points),
row by row in the same order on both sides (lock-previous carries from one row to the next).
A fuzzylite NaN ("no rule fired", default nan) must be 0 here; a fuzzylite +-inf is a saturated
sigmoid under Tsukamoto, where we give the end of the output range (docs/rule_files.md) and
which is not compared. KNOWN lists the files that are expected to differ, each with the reason;
the check fails when a file outside the list differs or a listed file agrees (stale list).
"""
import json
import math
import os
import subprocess
import sys
import tempfile

TOLERANCE = 1e-12
# Files where fuzzypid and fuzzylite 8 are known to differ, and why (docs/rule_files.md).
KNOWN = {
    "handmade_tsukamoto_concave.fll": ("fuzzylite 8 weighs rules of degree 0 too: a Concave "
                                       "term's z(0) is infinite and 0 * inf is NaN"),
    "fuzzylite5_style_activation_accumulation.fll": ("fuzzylite 8 does not read fuzzylite 5's "
                                                     "'accumulation' key"),
}

EVAL_FL8 = r"""
import json, sys, math
import fuzzylite as fl
path, rows = sys.argv[1], json.load(sys.stdin)
engine = fl.FllImporter().from_file(path)
out = []
for row in rows:
    for v, x in zip(engine.input_variables, row):
        v.value = x
    engine.process()
    out.append([float(o.value) for o in engine.output_variables])
print(json.dumps([[repr(y) for y in r] for r in out]))
"""


def grid(ranges, budget=400):
    n = len(ranges)
    k = max(2, int(budget ** (1.0 / n)))
    axes = []
    for lo, hi in ranges:
        lo = lo if math.isfinite(lo) else -10.0
        hi = hi if math.isfinite(hi) else 10.0
        margin = 0.1 * (hi - lo)
        a, b = lo - margin, hi + margin
        axes.append([a + (b - a) * (j + 0.37) / k for j in range(k)])
    rows = [[]]
    for axis in axes:
        rows = [r + [x] for r in rows for x in axis]
    return rows


def ranges_of(path):
    ranges, section = [], None
    for line in open(path, encoding="utf-8", errors="replace"):
        s = line.split("#")[0].strip()
        if s.startswith("InputVariable:"):
            section = "input"
            ranges.append([-math.inf, math.inf])
        elif s.startswith(("OutputVariable:", "RuleBlock:")):
            section = None
        elif section == "input" and s.startswith("range:"):
            lo, hi = s.split()[1:3]
            ranges[-1] = [float(lo), float(hi)]
    return ranges


def main():
    if len(sys.argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    venv_python, fuzzypid, corpus = sys.argv[1:]
    version = subprocess.run([venv_python, "-c", "import fuzzylite; print(fuzzylite.__version__)"],
                             capture_output=True, text=True) if os.path.exists(venv_python) else None
    if version is None or version.returncode != 0 or version.stdout.strip() != "8.0.6":
        print(f"SKIP: no pyfuzzylite 8.0.6 at {venv_python} (make it with scripts/oracle-venv.sh)")
        return 77
    files = sorted(f for f in os.listdir(corpus) if f.endswith(".fll") and not f.startswith("refuse_"))
    differing, agreeing_known, compared, skipped = [], [], 0, 0
    worst, worst_file = 0.0, ""
    for name in files:
        path = os.path.join(corpus, name)
        rows = grid(ranges_of(path))
        fl8 = subprocess.run([venv_python, "-c", EVAL_FL8, path], input=json.dumps(rows),
                             capture_output=True, text=True)
        if fl8.returncode != 0:
            print(f"  differs  {name}: fuzzylite 8 cannot evaluate it: "
                  f"{fl8.stderr.strip().splitlines()[-1:]}"
                  + (f"  [known: {KNOWN[name]}]" if name in KNOWN else ""))
            if name not in KNOWN:
                differing.append(name)
            continue
        expected = [[float(y) for y in r] for r in json.loads(fl8.stdout)]
        with tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False) as f:
            f.write(",".join(f"x{i}" for i in range(len(rows[0]))) + "\n")
            for r in rows:
                f.write(",".join(repr(x) for x in r) + "\n")
            csv = f.name
        with open(csv) as stdin:
            ours = subprocess.run([fuzzypid, "eval", "--fll", path], stdin=stdin,
                                  capture_output=True, text=True)
        os.unlink(csv)
        lines = ours.stdout.strip().splitlines()[1:]
        if ours.returncode not in (0, 1) or len(lines) != len(rows):
            print(f"{name}: fuzzypid eval failed (exit {ours.returncode}): {ours.stderr.strip()[:300]}")
            differing.append(name)
            continue
        n_in = len(rows[0])
        file_worst, where = 0.0, None
        for k, (line, want) in enumerate(zip(lines, expected)):
            got = [float(v) for v in line.split(",")[n_in:]]
            for o, (a, b) in enumerate(zip(got, want)):
                if math.isinf(b):
                    skipped += 1
                    continue
                if math.isnan(b):
                    b = 0.0  # fuzzylite's "no value" is 0 with NoRuleFired here
                compared += 1
                d = abs(a - b) / max(1.0, abs(b))
                if d > file_worst or (d != d):
                    file_worst, where = d, (rows[k], o, a, b)
        bad = not (file_worst <= TOLERANCE)
        if file_worst > worst and name not in KNOWN:
            worst, worst_file = file_worst, name
        status = "differs" if bad else "agrees"
        print(f"  {status:8} {name}: {len(rows)} points, max relative |fuzzypid - fuzzylite 8| = "
              f"{file_worst:.3g}" + (f" at inputs {where[0]} output {where[1]}: {where[2]!r} vs "
                                     f"{where[3]!r}" if bad else "")
              + (f"  [known: {KNOWN[name]}]" if name in KNOWN else ""))
        if bad and name not in KNOWN:
            differing.append(name)
        if not bad and name in KNOWN:
            agreeing_known.append(name)
    known = [name for name in files if name in KNOWN]
    print(f"fuzzylite 8: {len(files) - len(differing) - len(known) + len(agreeing_known)} of "
          f"{len(files)} .fll files agree to {TOLERANCE:g} ({len(known)} known differences); "
          f"{compared} values compared, largest relative difference {worst:.3g} ({worst_file}); "
          f"{skipped} saturated-sigmoid values not compared")
    for name in differing:
        print(f"FAIL: {name} differs from fuzzylite 8 and is not a known difference")
    for name in agreeing_known:
        print(f"FAIL: {name} is listed as a known difference but agrees: update KNOWN")
    return 1 if differing or agreeing_known else 0


if __name__ == "__main__":
    sys.exit(main())
