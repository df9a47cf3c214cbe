#!/usr/bin/python3
"""Closed-loop quality of the shipped controllers, against the figures the documentation states.

Runs sim_ab with every controller of a documented table (controllers/NAME.toml) on its condition
file and checks each row (set, controller): the summed ITAE within 0.5 % (the tables print four
significant digits) and the worst overshoot within 0.1 percentage points. A controller that tracks
worse, or a table that no longer says what the shipped files do, fails.

With a DRIVE_HEADING it also checks the first table under it, the drive metrics: per row (set,
controller) the worst joint's reversals_pct over the set's conditions without measurement noise
(the column headed "reversals %" or "reversals %, no noise") and its saturated_pct over all of
them ("saturated %"), each within 0.05 percentage points (the tables print one decimal); its rows
may also name the drive file's `encoders` set.

usage: check_documented_quality.py SIM_AB SOURCE_DIR WORK_DIR [DOC HEADING CONDITIONS ROWS
                                   [allow-faults [DRIVE_HEADING]]]
  (default: docs/tuning.md, "### The six-way table", tuning/robust.toml, 21 rows; no controller
  may fault -- sim_ab exits 1 -- unless allow-faults: a table that documents controllers which
  diverge or leave the joint limits)
"""
import collections
import csv
import os
import re
import subprocess
import sys


def documented(doc, heading):
    """Rows (set, controller) -> (itae, overshoot) of the first table under `heading`."""
    lines = open(doc, encoding="utf-8").read().split("\n")
    start = lines.index(heading)
    rows = {}
    for line in lines[start:]:
        if rows and not line.startswith("|"):
            break
        m = re.match(r"^\| (training|held-out|stress) \| (\w+) \| \d+ \| ([0-9.e+-]+) \| [0-9.]+ \| "
                     r"([0-9.]+) \|", line)
        if m:
            rows[(m.group(1), m.group(2))] = (float(m.group(3)), float(m.group(4)))
    return rows


def documented_drive(doc, heading):
    """Rows (set, controller) -> (reversals %, saturated %) of the first table after `heading`
    with a "saturated %" column."""
    lines = open(doc, encoding="utf-8").read().split("\n")
    columns, rows = None, {}
    for line in lines[lines.index(heading):]:
        if not line.startswith("|"):
            if rows:
                break
            columns = None
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if columns is None:
            columns = cells
            continue
        if "saturated %" not in columns:
            continue
        rev = next(i for i, c in enumerate(columns) if c in ("reversals %", "reversals %, no noise"))
        sat = columns.index("saturated %")
        documented_set = cells[0] in ("training", "held-out", "stress", "encoders")
        if documented_set and cells[rev] and cells[sat]:
            rows[(cells[0], cells[1])] = (float(cells[rev]), float(cells[sat]))
    return rows


def main():
    sim_ab, src, work = sys.argv[1:4]
    doc, heading, conditions, expected = "docs/tuning.md", "### The six-way table", \
        "tuning/robust.toml", 21
    if len(sys.argv) > 4:
        doc, heading, conditions, expected = sys.argv[4], sys.argv[5], sys.argv[6], int(sys.argv[7])
    rows = documented(os.path.join(src, doc), heading)
    if len(rows) != expected:
        sys.exit(f"expected {expected} rows in {doc}'s table '{heading}', found {len(rows)}")
    names = sorted({c for _, c in rows})
    out = os.path.join(work, "quality-" + os.path.basename(conditions).split(".")[0])
    cmd = [sim_ab, "--quiet", "--conditions", os.path.join(src, conditions), "--out", out]
    if len(sys.argv) > 8 and sys.argv[8] == "allow-faults":
        cmd.append("--allow-faults")
    for n in names:
        cmd += ["--controller", os.path.join(src, "controllers", n + ".toml")]
    run = subprocess.run(cmd, capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"sim_ab exited {run.returncode}: {run.stderr}")
    sets = {r["scenario"]: r["set"] for r in csv.DictReader(open(os.path.join(out, "conditions.csv")))}
    itae = collections.defaultdict(float)
    overshoot = collections.defaultdict(float)
    for r in csv.DictReader(open(os.path.join(out, "metrics.csv"))):
        key = (sets[r["scenario"]], r["controller"])
        itae[key] += float(r["itae"])
        overshoot[key] = max(overshoot[key], float(r["overshoot_pct"]))
    failures = 0
    for key, (want_itae, want_overshoot) in sorted(rows.items()):
        got_itae, got_overshoot = itae[key], overshoot[key]
        ok = abs(got_itae - want_itae) <= 5e-3 * want_itae and abs(got_overshoot - want_overshoot) <= 0.1
        print(f"{key[0]:9s} {key[1]:16s} ITAE {got_itae:.4g} (documented {want_itae:.4g}), "
              f"worst overshoot {got_overshoot:.1f} % (documented {want_overshoot:.1f} %)"
              f"{'' if ok else '  <-- FAIL'}")
        failures += 0 if ok else 1
    drive = documented_drive(os.path.join(src, doc), sys.argv[9]) if len(sys.argv) > 9 else {}
    if len(sys.argv) > 9 and not drive:
        sys.exit(f"no drive rows under '{sys.argv[9]}' in {doc}")
    noisy = {r["scenario"]: float(r["noise_q"]) > 0 or float(r["noise_qd"]) > 0
             for r in csv.DictReader(open(os.path.join(out, "conditions.csv")))}
    reversals = collections.defaultdict(float)
    saturated = collections.defaultdict(float)
    for r in csv.DictReader(open(os.path.join(out, "metrics.csv"))):
        key = (sets[r["scenario"]], r["controller"])
        if not noisy[r["scenario"]]:
            reversals[key] = max(reversals[key], float(r["reversals_pct"]))
        saturated[key] = max(saturated[key], float(r["saturated_pct"]))
    for key, (want_rev, want_sat) in sorted(drive.items()):
        got_rev, got_sat = reversals[key], saturated[key]
        ok = abs(got_rev - want_rev) <= 0.05 and abs(got_sat - want_sat) <= 0.05
        print(f"{key[0]:9s} {key[1]:16s} reversals {got_rev:.1f} % (documented {want_rev:.1f} %), "
              f"saturated {got_sat:.1f} % (documented {want_sat:.1f} %){'' if ok else '  <-- FAIL'}")
        failures += 0 if ok else 1
    if failures:
        sys.exit(f"{failures} row(s) differ from {doc}")
    print(f"all {len(rows) + len(drive)} documented rows hold")


if __name__ == "__main__":
    main()
