#!/usr/bin/python3
"""Summarises the seed study of scripts/tune.sh (docs/tuning.md).

usage: scripts/seed_study.py DIR     (DIR: a sim_ab --out directory whose controllers are named
                                      <family>_seed<S>, family pid, scheduled, fuzzy, fuzzy_rules,
                                      and paper_pid, paper_fuzzy)

For every set and family: the summed ITAE (six joints, all conditions of the set) per seed, its
median and range. Then per seed S the ratios of summed ITAE fuzzy_rules / scheduled, fuzzy /
scheduled and fuzzy / pid with the conditions each wins (and, when present, the control
scheduled_staged: a schedule started from the same PID stage with the same total budget); the worst overshoot of each family on the
held-out set; and, per stress condition, fuzzy_rules / scheduled. Last, the issue's targets for the
fuzzy-rules family: median held-out ratio <= 0.85 and no seed above 1.0; no stress condition worse
than the schedule by more than 10 %; worst held-out overshoot <= 25 %.
"""
import collections
import csv
import re
import statistics
import sys

FAMILIES = ("pid", "scheduled", "fuzzy", "fuzzy_rules", "scheduled_staged")


def main():
    d = sys.argv[1] if len(sys.argv) > 1 else "out/seeds/eval"
    sets = {r["scenario"]: r["set"] for r in csv.DictReader(open(f"{d}/conditions.csv"))}
    itae = collections.defaultdict(float)  # (controller, condition) -> sum over joints
    overshoot = collections.defaultdict(float)  # (controller, condition) -> max over joints
    for r in csv.DictReader(open(f"{d}/metrics.csv")):
        key = (r["controller"], r["scenario"])
        itae[key] += float(r["itae"])
        overshoot[key] = max(overshoot[key], float(r["overshoot_pct"]))
    runs = collections.defaultdict(dict)  # family -> seed -> controller
    for (c, _) in itae:
        m = re.fullmatch(r"(fuzzy_rules|scheduled_staged|pid|scheduled|fuzzy)_seed(\d+)", c)
        if m:
            runs[m.group(1)][int(m.group(2))] = c
    set_names = sorted(set(sets.values()), key=lambda s: (s != "training", s))
    conds_of = {s: [c for c, v in sets.items() if v == s] for s in set_names}

    def total(controller, s):
        return sum(itae[(controller, c)] for c in conds_of[s])

    print("| set | controller | summed ITAE per seed | median | range (max/min) |")
    print("|---|---|---|---|---|")
    for s in set_names:
        for paper in ("paper_pid", "paper_fuzzy"):
            if (paper, conds_of[s][0]) in itae:
                print(f"| {s} | {paper} | {total(paper, s):.4g} | | |")
        for fam in FAMILIES:
            vals = [total(runs[fam][k], s) for k in sorted(runs[fam])]
            if vals:
                print(f"| {s} | {fam} | {', '.join(f'{v:.4g}' for v in vals)} |"
                      f" {statistics.median(vals):.4g} | {max(vals) / min(vals):.3f} |")
    print()
    print("| set | ratio | per seed | median | min | max | lower ITAE on (conditions, per seed) |")
    print("|---|---|---|---|---|---|---|")
    ratios_of = {}
    for s in set_names:
        for a, b in (("fuzzy_rules", "scheduled"), ("fuzzy_rules", "scheduled_staged"),
                     ("scheduled_staged", "scheduled"), ("fuzzy_rules", "pid"),
                     ("fuzzy", "scheduled"), ("fuzzy", "pid")):
            ratios, wins = [], []
            for k in sorted(set(runs[a]) & set(runs[b])):
                ratios.append(total(runs[a][k], s) / total(runs[b][k], s))
                wins.append(sum(1 for c in conds_of[s] if itae[(runs[a][k], c)] < itae[(runs[b][k], c)]))
            if not ratios:
                continue
            ratios_of[(s, a, b)] = ratios
            print(f"| {s} | {a} / {b} | {', '.join(f'{r:.3f}' for r in ratios)} |"
                  f" {statistics.median(ratios):.3f} | {min(ratios):.3f} | {max(ratios):.3f} |"
                  f" {', '.join(f'{w}/{len(conds_of[s])}' for w in wins)} |")
    print()
    print("| family | worst held-out overshoot % per seed |")
    print("|---|---|")
    worst_rules = []
    for fam in FAMILIES:
        worst = [max(overshoot[(runs[fam][k], c)] for c in conds_of.get("held-out", []))
                 for k in sorted(runs[fam])] if "held-out" in conds_of else []
        if worst:
            print(f"| {fam} | {', '.join(f'{w:.1f}' for w in worst)} |")
        if fam == "fuzzy_rules":
            worst_rules = worst
    print()
    stress_worst = []
    if "stress" in conds_of:
        print("| stress condition | fuzzy_rules / scheduled ITAE per seed |")
        print("|---|---|")
        for c in conds_of["stress"]:
            r = [itae[(runs["fuzzy_rules"][k], c)] / itae[(runs["scheduled"][k], c)]
                 for k in sorted(set(runs["fuzzy_rules"]) & set(runs["scheduled"]))]
            stress_worst += r
            print(f"| {c} | {', '.join(f'{x:.3f}' for x in r)} |")
        print()
    held = ratios_of.get(("held-out", "fuzzy_rules", "scheduled"), [])
    if held:
        checks = [
            ("median held-out fuzzy_rules / scheduled <= 0.85", statistics.median(held) <= 0.85,
             f"{statistics.median(held):.3f}"),
            ("no seed above 1.0", max(held) <= 1.0, f"max {max(held):.3f}"),
            ("no stress condition worse than the schedule by > 10 %",
             bool(stress_worst) and max(stress_worst) <= 1.10,
             f"max {max(stress_worst):.3f}" if stress_worst else "no stress set"),
            ("worst held-out overshoot <= 25 %", bool(worst_rules) and max(worst_rules) <= 25.0,
             f"max {max(worst_rules):.1f} %" if worst_rules else "no held-out set"),
        ]
        print("| target | met | measured |")
        print("|---|---|---|")
        for name, ok, value in checks:
            print(f"| {name} | {'yes' if ok else 'no'} | {value} |")


if __name__ == "__main__":
    main()
