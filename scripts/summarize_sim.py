#!/usr/bin/python3
"""Prints sim_ab results as Markdown tables (the tables of docs/reproduction.md).

usage: scripts/summarize_sim.py [DIR]     (DIR defaults to out)

Per scenario and controller, over the six joints: the worst and the median settling time, the
largest overshoot, the largest |error| after the first second and at the last tick, and the summed
ITAE -- all from DIR/metrics.csv and DIR/trajectory.csv. Then the per-joint metrics of the paper
scenario.
"""
import collections
import csv
import sys


def fmt_s(x):
    return "not settled" if x == float("inf") else f"{x:.2f}"


def main():
    d = sys.argv[1] if len(sys.argv) > 1 else "out"
    metrics = list(csv.DictReader(open(f"{d}/metrics.csv", newline="")))
    traj = list(csv.DictReader(open(f"{d}/trajectory.csv", newline="")))
    late = collections.defaultdict(float)
    final = collections.defaultdict(float)
    t_end = collections.defaultdict(float)
    for r in traj:
        key = (r["scenario"], r["controller"])
        t_end[key] = max(t_end[key], float(r["t"]))
    for r in traj:
        key = (r["scenario"], r["controller"])
        e = abs(float(r["error"]))
        if float(r["t"]) >= 1.0 - 1e-9:
            late[key] = max(late[key], e)
        if abs(float(r["t"]) - t_end[key]) < 1e-9:
            final[key] = max(final[key], e)
    groups = collections.OrderedDict()
    for r in metrics:
        groups.setdefault((r["scenario"], r["controller"]), []).append(r)
    print("| scenario | controller | settling, worst joint (s) | settling, median joint (s) |"
          " max overshoot (%) | max abs(e) for t >= 1 s (rad) | max abs(e) at t = 5 s (rad) |"
          " ITAE, sum of joints |")
    print("|---|---|---|---|---|---|---|---|")
    for (s, c), rows in groups.items():
        st = sorted(float(r["settling_time_s"]) for r in rows)
        median = 0.5 * (st[2] + st[3])
        print(f"| {s} | {c} | {fmt_s(st[-1])} | {fmt_s(median)} |"
              f" {max(float(r['overshoot_pct']) for r in rows):.1f} | {late[(s, c)]:.2e} |"
              f" {final[(s, c)]:.2e} | {sum(float(r['itae']) for r in rows):.3e} |")
    print()
    print("| controller | joint | settling (s) | overshoot (%) | max abs(e) (rad) | rms e (rad) |"
          " IAE | ITAE |")
    print("|---|---|---|---|---|---|---|---|")
    for (s, c), rows in groups.items():
        if s != "paper":
            continue
        for r in rows:
            print(f"| {c} | {r['joint']} | {fmt_s(float(r['settling_time_s']))} |"
                  f" {float(r['overshoot_pct']):.1f} | {float(r['max_abs_error_rad']):.2e} |"
                  f" {float(r['rms_error_rad']):.2e} | {float(r['iae']):.3e} |"
                  f" {float(r['itae']):.3e} |")


if __name__ == "__main__":
    main()
