#!/usr/bin/python3
"""Plots fronts (fuzzypid tune --front-out DIR) and prints their hypervolumes (docs/tuning.md).

usage: scripts/plot_front.py DIR [DIR...] [--on training|validation] [--out PNG]
                             [--drop-at X] [--fuzzypid PATH]

One panel: per DIR (labelled by its folder name) its points, ITAE on x (log scale) against effort
on y, coloured by overshoot; without those objectives, the first two coloured by the third if
any. --on chooses the columns (default training; validation holds the --validation or
--report-set conditions). Points with an objective at or above --drop-at (the fault cost: a run
that faulted) are left out of the plot and the hypervolumes. Then runs `fuzzypid hypervolume`
(--fuzzypid, default build/bin/fuzzypid) on the same fronts and prints its CSV. Writes --out
(default fronts.png). Exits 1 on a missing or malformed front. Runs with Debian's
python3-matplotlib.
"""
import argparse
import csv
import math
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

MARKERS = "osD^v<>px*"


def read(d, on):
    try:
        with open(os.path.join(d, "front.csv"), newline="") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        sys.exit(f"plot_front.py: {d}/front.csv: {e.strerror}")
    if len(rows) < 2 or rows[0][:2] != ["point", "file"]:
        sys.exit(f"plot_front.py: {d}/front.csv is not a front")
    names = [h for h in rows[0][2:] if not h.startswith("validation_")]
    prefix = "" if on == "training" else "validation_"
    try:
        cols = [rows[0].index(prefix + n) for n in names]
        points = [[float(r[c]) for c in cols] for r in rows[1:]]
    except (ValueError, IndexError):
        sys.exit(f"plot_front.py: {d}/front.csv: no {on} columns or a malformed row")
    if not all(math.isfinite(v) for p in points for v in p):
        sys.exit(f"plot_front.py: {d}/front.csv: a value that is not finite")
    return names, points


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dirs", nargs="+")
    ap.add_argument("--on", choices=["training", "validation"], default="training")
    ap.add_argument("--out", default="fronts.png")
    ap.add_argument("--drop-at", type=float)
    ap.add_argument("--fuzzypid", default="build/bin/fuzzypid")
    a = ap.parse_args()
    fronts = [(d, *read(d, a.on)) for d in a.dirs]
    names = fronts[0][1]
    for d, n, _ in fronts:
        if n != names:
            sys.exit(f"plot_front.py: {d} has objectives {n}, {a.dirs[0]} has {names}")
    pick = [names.index(n) for n in ("itae", "effort", "overshoot") if n in names]
    if len(pick) < 2:
        pick = list(range(min(3, len(names))))
    x, y = pick[0], pick[1]
    c = pick[2] if len(pick) > 2 else None
    fig, ax = plt.subplots(figsize=(8, 6))
    scatter = None
    for k, (d, _, points) in enumerate(fronts):
        if a.drop_at is not None:
            points = [p for p in points if max(p) < a.drop_at]
        if not points:
            continue
        label = os.path.basename(os.path.normpath(d))
        colours = [p[c] for p in points] if c is not None else None
        scatter = ax.scatter([p[x] for p in points], [p[y] for p in points], c=colours,
                             cmap="viridis", marker=MARKERS[k % len(MARKERS)], label=label,
                             edgecolors="k", linewidths=0.4)
    ax.set_xscale("log")
    ax.set_xlabel(f"{names[x]} ({a.on})")
    ax.set_ylabel(f"{names[y]} ({a.on})")
    if c is not None and scatter is not None:
        fig.colorbar(scatter, ax=ax, label=f"{names[c]} ({a.on})")
    ax.legend()
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(a.out, dpi=120)
    print(f"plot_front.py: wrote {a.out}", file=sys.stderr)
    cmd = [a.fuzzypid, "hypervolume", *a.dirs, "--on", a.on]
    if a.drop_at is not None:
        cmd += ["--drop-at", repr(a.drop_at)]
    try:
        done = subprocess.run(cmd, check=False)
    except OSError as e:
        sys.exit(f"plot_front.py: {a.fuzzypid}: {e.strerror}")
    sys.exit(done.returncode)


if __name__ == "__main__":
    main()
