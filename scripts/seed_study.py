#!/usr/bin/python3
"""Summarises the seed study of scripts/tune.sh (docs/tuning.md).

usage: scripts/seed_study.py DIR     (DIR: a sim_ab --out directory whose controllers are named
                                      <family>_seed<S>)

For every set of the conditions file and every family, the summed ITAE (six joints, all
conditions of the set) per seed, its median and range; then, per seed S, the ratios
fuzzy_seedS / pid_seedS and fuzzy_seedS / scheduled_seedS of the summed ITAE and the number of
conditions on which the fuzzy PID has the lower ITAE; their median and range over the seeds.
"""
import collections
import csv
import re
import statistics
import sys


def main():
    d = sys.argv[1] if len(sys.argv) > 1 else "out/seeds/eval"
    sets = {r["scenario"]: r["set"] for r in csv.DictReader(open(f"{d}/conditions.csv"))}
    itae = collections.defaultdict(float)  # (controller, condition) -> sum over joints
    for r in csv.DictReader(open(f"{d}/metrics.csv")):
        itae[(r["controller"], r["scenario"])] += float(r["itae"])
    runs = collections.defaultdict(dict)  # family -> seed -> controller
    for (c, _) in itae:
        m = re.fullmatch(r"(pid|scheduled|fuzzy)_seed(\d+)", c)
        if m:
            runs[m.group(1)][int(m.group(2))] = c
    set_names = sorted(set(sets.values()), key=lambda s: (s != "training", s))
    print("| set | family | summed ITAE per seed | median | range (max/min) |")
    print("|---|---|---|---|---|")
    for s in set_names:
        conds = [c for c, v in sets.items() if v == s]
        for fam in ("pid", "scheduled", "fuzzy"):
            vals = [sum(itae[(runs[fam][k], c)] for c in conds) for k in sorted(runs[fam])]
            if not vals:
                continue
            print(f"| {s} | {fam} | {', '.join(f'{v:.4g}' for v in vals)} |"
                  f" {statistics.median(vals):.4g} | {max(vals) / min(vals):.3f} |")
    print()
    print("| set | ratio | per seed | median | min | max | fuzzy lower ITAE on (conditions, per seed) |")
    print("|---|---|---|---|---|---|---|")
    for s in set_names:
        conds = [c for c, v in sets.items() if v == s]
        for other in ("pid", "scheduled"):
            ratios, wins = [], []
            for k in sorted(set(runs["fuzzy"]) & set(runs[other])):
                f, o = runs["fuzzy"][k], runs[other][k]
                ratios.append(sum(itae[(f, c)] for c in conds) / sum(itae[(o, c)] for c in conds))
                wins.append(sum(1 for c in conds if itae[(f, c)] < itae[(o, c)]))
            if not ratios:
                continue
            print(f"| {s} | fuzzy / {other} | {', '.join(f'{r:.3f}' for r in ratios)} |"
                  f" {statistics.median(ratios):.3f} | {min(ratios):.3f} | {max(ratios):.3f} |"
                  f" {', '.join(f'{w}/{len(conds)}' for w in wins)} |")


if __name__ == "__main__":
    main()
