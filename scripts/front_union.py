#!/usr/bin/python3
"""Which families are on the front of several fronts together (docs/tuning.md, "Fronts").

usage: scripts/front_union.py DIR [DIR...] [--on training|validation]

Each DIR is a front written by `fuzzypid tune --objectives ... --front-out DIR` (front.csv). The
points of all DIRs are pooled and compared on the chosen columns (training by default; validation
holds the --validation or --report-set conditions, never seen by the search); a point is on the
pooled front when no point of any DIR dominates it (no worse in every objective, better in one).
Prints a Markdown table: per DIR its points, how many are on the pooled front, and its best value
of each objective. Exits 1 on a missing or malformed front.csv, or fronts of other objectives.
"""
import csv
import math
import sys


def read_front(d, on):
    try:
        with open(f"{d}/front.csv", newline="") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        sys.exit(f"front_union.py: {d}: {e.strerror}")
    if len(rows) < 2 or rows[0][:2] != ["point", "file"]:
        sys.exit(f"front_union.py: {d}/front.csv is not a front (header point,file,...)")
    header = rows[0]
    names = [h for h in header[2:] if not h.startswith("validation_")]
    cols = [header.index(n if on == "training" else "validation_" + n)
            if (n if on == "training" else "validation_" + n) in header else -1 for n in names]
    if -1 in cols:
        sys.exit(f"front_union.py: {d}/front.csv has no {on} columns")
    points = []
    for k, r in enumerate(rows[1:], start=2):
        if len(r) != len(header):
            sys.exit(f"front_union.py: {d}/front.csv:{k}: {len(r)} fields, expected {len(header)}")
        try:
            v = [float(r[c]) for c in cols]
        except ValueError:
            sys.exit(f"front_union.py: {d}/front.csv:{k}: not a number")
        if not all(math.isfinite(x) for x in v):
            sys.exit(f"front_union.py: {d}/front.csv:{k}: not a finite number")
        points.append(v)
    return names, points


def dominates(a, b):
    return all(x <= y for x, y in zip(a, b)) and any(x < y for x, y in zip(a, b))


def main():
    args = sys.argv[1:]
    on = "training"
    if "--on" in args:
        i = args.index("--on")
        if i + 1 >= len(args) or args[i + 1] not in ("training", "validation"):
            sys.exit("front_union.py: --on training|validation")
        on = args[i + 1]
        del args[i:i + 2]
    if not args:
        sys.exit(__doc__.strip().splitlines()[2])
    fronts = []
    names = None
    for d in args:
        n, p = read_front(d, on)
        if names is not None and n != names:
            sys.exit(f"front_union.py: {d} has objectives {n}, {args[0]} has {names}")
        names = n
        fronts.append((d, p))
    pooled = [v for _, p in fronts for v in p]
    print(f"| front ({on}) | points | on the pooled front | " +
          " | ".join(f"best {n}" for n in names) + " |")
    print("|---|---|---|" + "---|" * len(names))
    for d, p in fronts:
        on_front = sum(1 for v in p if not any(dominates(w, v) for w in pooled))
        best = [min(v[i] for v in p) for i in range(len(names))]
        print(f"| {d} | {len(p)} | {on_front} | " + " | ".join(f"{b:.4g}" for b in best) + " |")


if __name__ == "__main__":
    main()
