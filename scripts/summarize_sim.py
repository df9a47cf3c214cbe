#!/usr/bin/python3
"""Prints sim_ab results as Markdown tables (docs/reproduction.md, docs/tuning.md).

usage: scripts/summarize_sim.py [DIR] [--per-condition] [--gains] [--drive]   (DIR defaults to out)

1. Per set (conditions.csv; "scenario" when sim_ab ran --scenario) and controller, over the set's
   conditions and the six joints: summed ITAE, its ratio to the first controller... of the tuned
   ones (tuned_pid when present), the worst overshoot, how many conditions overshoot more than
   20 %, the worst settling time and the largest |error| after the first second.
2. --per-condition: summed ITAE (six joints) per condition and controller.
3. --gains: the range of each controller's gains over every tick of the set (file units), and
   relative to its nominal gains K0 (settings.txt).
4. --drive: per set and controller, the worst joint's reversals_pct and sign_changes_pct
   (maximum over the set's conditions without measurement noise, and over those with it),
   saturated_pct and tcp_error_max_mm (maximum over all), and the runs with faults.
Without a set column (scenario runs) it also prints the per-joint metrics of the paper scenario.
"""
import collections
import csv
import math
import sys


def fmt_s(x):
    return "not settled" if x == float("inf") else f"{x:.2f}"


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    d = args[0] if args else "out"
    metrics = list(csv.DictReader(open(f"{d}/metrics.csv", newline="")))
    sets = collections.OrderedDict()
    try:
        for r in csv.DictReader(open(f"{d}/conditions.csv", newline="")):
            sets[r["scenario"]] = r["set"]
    except FileNotFoundError:
        pass
    controllers = list(dict.fromkeys(r["controller"] for r in metrics))
    conds = list(dict.fromkeys(r["scenario"] for r in metrics))
    by = collections.defaultdict(list)
    for r in metrics:
        by[(r["scenario"], r["controller"])].append(r)
    itae = {k: sum(float(r["itae"]) for r in rows) for k, rows in by.items()}
    set_names = list(dict.fromkeys(sets.get(c, "scenario") for c in conds))
    ref = "tuned_pid" if "tuned_pid" in controllers else controllers[0]

    print(f"| set | controller | conditions | ITAE, sum | ITAE / {ref} | worst overshoot (%) |"
          " conditions with overshoot > 20 % | worst settling (s) | max abs(e) for t >= 1 s (rad) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for s in set_names:
        cs = [c for c in conds if sets.get(c, "scenario") == s]
        ref_sum = sum(itae[(c, ref)] for c in cs)
        for ctl in controllers:
            rows = [r for c in cs for r in by[(c, ctl)]]
            total = sum(itae[(c, ctl)] for c in cs)
            over = sum(1 for c in cs if max(float(r["overshoot_pct"]) for r in by[(c, ctl)]) > 20.0)
            print(f"| {s} | {ctl} | {len(cs)} | {total:.4g} | {total / ref_sum:.3f} |"
                  f" {max(float(r['overshoot_pct']) for r in rows):.1f} | {over} |"
                  f" {fmt_s(max(float(r['settling_time_s']) for r in rows))} |"
                  f" {max(float(r['max_abs_error_after_1s_rad']) for r in rows):.2e} |")

    if "--per-condition" in sys.argv:
        print()
        print("| set | condition | " + " | ".join(controllers) + " |")
        print("|---|---|" + "---|" * len(controllers))
        for c in conds:
            best = min(itae[(c, k)] for k in controllers)
            cells = [(f"**{itae[(c, k)]:.3e}**" if itae[(c, k)] == best else f"{itae[(c, k)]:.3e}")
                     for k in controllers]
            print(f"| {sets.get(c, 'scenario')} | {c} | " + " | ".join(cells) + " |")

    if "--gains" in sys.argv:
        traj = csv.DictReader(open(f"{d}/trajectory.csv", newline=""))
        lo = collections.defaultdict(lambda: [math.inf] * 3)
        hi = collections.defaultdict(lambda: [-math.inf] * 3)
        first = {}
        for line in open(f"{d}/settings.txt"):
            if line.startswith("controller."):
                name = line.split("=", 1)[0][len("controller."):]
                for field in line.split():
                    if field.startswith("gains="):
                        first[name] = [float(v) for v in field[len("gains="):].split(",")]
        for r in traj:
            s = sets.get(r["scenario"], "scenario")
            g = [float(r["kp"]), float(r["ki"]), float(r["kd"])]
            key = (s, r["controller"])
            for i in range(3):
                lo[key][i] = min(lo[key][i], g[i])
                hi[key][i] = max(hi[key][i], g[i])
        print()
        print("| set | controller | Kp range | Ki range | Kd range | Kp, Kd relative to K0 |")
        print("|---|---|---|---|---|---|")
        for (s, c), l in lo.items():
            h = hi[(s, c)]
            # Ki is left out: its K0 is often tiny, so percentages say nothing.
            rel = ", ".join(
                f"{n} {100 * (l[i] / first[c][i] - 1):+.1f} % .. {100 * (h[i] / first[c][i] - 1):+.1f} %"
                if first[c][i] else f"{n} -"
                for i, n in ((0, "Kp"), (2, "Kd")))
            print(f"| {s} | {c} | {l[0]:.4g} .. {h[0]:.4g} | {l[1]:.4g} .. {h[1]:.4g} |"
                  f" {l[2]:.4g} .. {h[2]:.4g} | {rel} |")

    if "--drive" in sys.argv:
        noisy = {}
        try:
            for r in csv.DictReader(open(f"{d}/conditions.csv", newline="")):
                noisy[r["scenario"]] = float(r["noise_q"]) > 0 or float(r["noise_qd"]) > 0
        except FileNotFoundError:
            pass

        def worst(cs, ctl, key, with_noise=None):
            values = [max(float(r[key]) for r in by[(c, ctl)]) for c in cs
                      if with_noise is None or noisy.get(c, False) == with_noise]
            return f"{max(values):.1f}" if values else "-"

        print()
        print("| set | controller | reversals % (no noise) | reversals % (noise) |"
              " sign changes % (no noise) | sign changes % (noise) | saturated % |"
              " max tool-path error (mm) | runs with faults |")
        print("|---|---|---|---|---|---|---|---|---|")
        for s in set_names:
            cs = [c for c in conds if sets.get(c, "scenario") == s]
            for ctl in controllers:
                faults = sum(1 for c in cs if int(by[(c, ctl)][0]["faults"]) > 0)
                print(f"| {s} | {ctl} | {worst(cs, ctl, 'reversals_pct', False)} |"
                      f" {worst(cs, ctl, 'reversals_pct', True)} |"
                      f" {worst(cs, ctl, 'sign_changes_pct', False)} |"
                      f" {worst(cs, ctl, 'sign_changes_pct', True)} |"
                      f" {worst(cs, ctl, 'saturated_pct')} |"
                      f" {max(float(by[(c, ctl)][0]['tcp_error_max_mm']) for c in cs):.3g} |"
                      f" {faults} |")

    if not sets or set(sets.values()) == {"scenario"}:
        print()
        print("| controller | joint | settling (s) | overshoot (%) | max abs(e) (rad) | rms e (rad) |"
              " IAE | ITAE |")
        print("|---|---|---|---|---|---|---|---|")
        for (s, c), rows in by.items():
            if s != "paper":
                continue
            for r in rows:
                print(f"| {c} | {r['joint']} | {fmt_s(float(r['settling_time_s']))} |"
                      f" {float(r['overshoot_pct']):.1f} | {float(r['max_abs_error_rad']):.2e} |"
                      f" {float(r['rms_error_rad']):.2e} | {float(r['iae']):.3e} |"
                      f" {float(r['itae']):.3e} |")


if __name__ == "__main__":
    main()
