#!/usr/bin/python3
"""Plots a fuzzy-rules controller's gain-ratio surfaces K/K0 over (e, ec), one per gain.

usage: scripts/plot_rule_surfaces.py [--fuzzypid BIN] [--contour] CONTROLLER.toml|SURFACE.csv OUT.png

The numbers come from the C++ side: a controller file is first turned into a grid by
`fuzzypid export-rules CONTROLLER --surface CSV` (the same RuleTable the controller runs; BIN
defaults to $FUZZYPID, else build/bin/fuzzypid beside this script's checkout, else `fuzzypid` on
the PATH); a CSV written that way is plotted as it is. The ratios are the supervisor's, before the
controller's gain bounds clamp them. Writes OUT.png with three 3-D surfaces (kp, ki, kd), or
filled contours with --contour. Runs with Debian's python3-matplotlib and python3-numpy.
"""
import argparse
import csv
import os
import shutil
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

COLUMNS = ("e_rad", "ec_rad_s", "kp_ratio", "ki_ratio", "kd_ratio")


def fuzzypid_binary(given):
    if given:
        return given
    if os.environ.get("FUZZYPID"):
        return os.environ["FUZZYPID"]
    here = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build", "bin",
                        "fuzzypid")
    if os.access(here, os.X_OK):
        return here
    found = shutil.which("fuzzypid")
    if found:
        return found
    sys.exit("plot_rule_surfaces: no fuzzypid binary: build it or pass --fuzzypid")


def read_grid(path):
    """The CSV as (e, ec, [kp, ki, kd]) arrays shaped n x n (rows: e, columns: ec)."""
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    if not rows or tuple(rows[0]) != COLUMNS:
        sys.exit(f"plot_rule_surfaces: {path}: expected the header {','.join(COLUMNS)}")
    data = np.array([[float(v) for v in r] for r in rows[1:]])
    n = int(round(len(data) ** 0.5))
    if n < 2 or n * n != len(data):
        sys.exit(f"plot_rule_surfaces: {path}: {len(data)} rows are no square grid")
    grid = data.reshape(n, n, len(COLUMNS))
    return grid[:, :, 0], grid[:, :, 1], [grid[:, :, k] for k in (2, 3, 4)]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("input", help="fuzzy-rules controller file (.toml) or export-rules --surface CSV")
    ap.add_argument("out", help="PNG to write")
    ap.add_argument("--fuzzypid", default=None, help="the fuzzypid binary")
    ap.add_argument("--points", type=int, default=41, help="grid points per axis (default 41)")
    ap.add_argument("--contour", action="store_true", help="filled contours instead of surfaces")
    a = ap.parse_args()

    title = os.path.basename(a.input)
    with tempfile.TemporaryDirectory() as tmp:
        csv_path = a.input
        if not a.input.endswith(".csv"):
            csv_path = os.path.join(tmp, "surface.csv")
            cmd = [fuzzypid_binary(a.fuzzypid), "export-rules", a.input, "--surface", csv_path,
                   "--surface-points", str(a.points)]
            done = subprocess.run(cmd, stderr=subprocess.PIPE, text=True)
            if done.returncode != 0:
                sys.exit(f"plot_rule_surfaces: {' '.join(cmd)} failed "
                         f"(exit {done.returncode}): {done.stderr.strip()}")
        e, ec, ratios = read_grid(csv_path)

    fig = plt.figure(figsize=(16, 5))
    for k, (name, z) in enumerate(zip(("Kp", "Ki", "Kd"), ratios)):
        if a.contour:
            ax = fig.add_subplot(1, 3, k + 1)
            filled = ax.contourf(e, ec, z, levels=20, cmap="viridis")
            fig.colorbar(filled, ax=ax, shrink=0.8)
        else:
            ax = fig.add_subplot(1, 3, k + 1, projection="3d")
            ax.plot_surface(e, ec, z, cmap="viridis", linewidth=0, antialiased=True)
            ax.set_zlabel(f"{name} / {name}0")
            ax.set_box_aspect(None, zoom=0.85)  # room for the z label
        ax.set_xlabel("e / rad")
        ax.set_ylabel("ec / (rad/s)")
        ax.set_title(f"{name} / {name}0")
    fig.suptitle(f"Gain ratios of {title} (schedule ramp x rule table, before the gain bounds)")
    fig.savefig(a.out, dpi=100, bbox_inches="tight")
    plt.close(fig)
    print(f"plot_rule_surfaces: wrote {a.out}")


if __name__ == "__main__":
    main()
