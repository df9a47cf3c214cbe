#!/usr/bin/python3
"""Turns sim_ab's CSV files into the paper's figures (Figs. 9-14) plus a per-scenario summary.

usage: scripts/plot_sim.py [--in DIR] [--out DIR] [--scenario NAME]
       scripts/plot_sim.py --sweep DIR [--out DIR]

Reads DIR/trajectory.csv, DIR/metrics.csv and DIR/endeffector.csv (default DIR = out) and writes
fig09_path.png, fig10_joints.png, fig11_errors.png, fig12_kp.png, fig13_ki.png, fig14_kd.png
(for --scenario, default paper) and summary.png (every scenario present) into --out (default: the
input directory). With --sweep, reads DIR/sweep.csv (sim_ab --sweep) and writes
sweep_<parameter>.png: summed ITAE and worst overshoot of every controller over the swept
parameter, usable points filled. Runs with Debian's python3-matplotlib and python3-numpy.
"""
import argparse
import collections
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STYLE = {"pid": ("k", "--"), "fuzzy": ("r", "-"), "paper_pid": ("k", "--"),
         "paper_fuzzy": ("r", "--"), "tuned_pid": ("tab:blue", "-"),
         "tuned_scheduled": ("tab:green", "-"), "tuned_fuzzy": ("tab:red", "-")}


def plot_sweep(inp, out):
    rows = read_csv(os.path.join(inp, "sweep.csv"))
    if not rows:
        sys.exit(f"plot_sim: {inp}/sweep.csv is empty")
    param = rows[0]["parameter"]
    ctrls = list(dict.fromkeys(r["controller"] for r in rows))
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(13, 4.5))
    for c in ctrls:
        pts = [r for r in rows if r["controller"] == c]
        col, ls = STYLE.get(c, ("g", "-"))
        x = [float(r["value"]) for r in pts]
        itae = [float(r["itae"]) for r in pts]
        over = [float(r["max_overshoot_pct"]) for r in pts]
        ax1.plot(x, itae, color=col, ls=ls, label=c)
        ax2.plot(x, over, color=col, ls=ls, label=c)
        for ax, ys in ((ax1, itae), (ax2, over)):
            ok = [(xi, yi) for xi, yi, r in zip(x, ys, pts) if r["usable"] == "1"]
            ax.plot([p[0] for p in ok], [p[1] for p in ok], "o", color=col, ms=3)
    ax1.set_yscale("log")
    ax2.set_yscale("symlog", linthresh=1.0)
    ax1.set_title("summed ITAE (dots: usable)")
    ax2.set_title("worst overshoot / % (dots: usable)")
    for ax in (ax1, ax2):
        ax.set_xlabel(param)
        ax.legend(fontsize=8)
    fig.suptitle(f"Robustness sweep over {param}")
    name = os.path.join(out, f"sweep_{param}.png")
    fig.savefig(name, dpi=110, bbox_inches="tight")
    plt.close(fig)
    print(f"plot_sim: wrote {name}")


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def series(rows, scenario, controller, joint, column):
    pts = [(float(r["t"]), float(r[column])) for r in rows
           if r["scenario"] == scenario and r["controller"] == controller and int(r["joint"]) == joint]
    return [p[0] for p in pts], [p[1] for p in pts]


def controllers_of(rows, scenario):
    seen = []
    for r in rows:
        if r["scenario"] == scenario and r["controller"] not in seen:
            seen.append(r["controller"])
    return seen


def joint_grid(title):
    fig, axes = plt.subplots(2, 3, figsize=(13, 7), sharex=True)
    fig.suptitle(title)
    return fig, axes.ravel()


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--in", dest="inp", default="out")
    ap.add_argument("--out", default=None)
    ap.add_argument("--scenario", default="paper")
    ap.add_argument("--sweep", default=None)
    a = ap.parse_args()
    if a.sweep:
        os.makedirs(a.out or a.sweep, exist_ok=True)
        plot_sweep(a.sweep, a.out or a.sweep)
        return
    out = a.out or a.inp
    os.makedirs(out, exist_ok=True)
    try:
        traj = read_csv(os.path.join(a.inp, "trajectory.csv"))
        metrics = read_csv(os.path.join(a.inp, "metrics.csv"))
        tip = read_csv(os.path.join(a.inp, "endeffector.csv"))
    except OSError as e:
        sys.exit(f"plot_sim: {e} (run build/bin/sim_ab first)")
    sc = a.scenario
    ctrls = controllers_of(traj, sc)
    if not ctrls:
        sys.exit(f"plot_sim: scenario '{sc}' not in {a.inp}/trajectory.csv")

    # Fig. 9: end-effector path in 3-D, mm.
    fig = plt.figure(figsize=(7, 6))
    ax = fig.add_subplot(projection="3d")
    ref = [r for r in tip if r["scenario"] == sc and r["controller"] == ctrls[0]]
    ax.plot([1e3 * float(r["x_d"]) for r in ref], [1e3 * float(r["y_d"]) for r in ref],
            [1e3 * float(r["z_d"]) for r in ref], color="0.6", lw=4, label="reference A→B")
    for c in ctrls:
        pts = [r for r in tip if r["scenario"] == sc and r["controller"] == c]
        col, ls = STYLE.get(c, ("g", "-"))
        ax.plot([1e3 * float(r["x"]) for r in pts], [1e3 * float(r["y"]) for r in pts],
                [1e3 * float(r["z"]) for r in pts], color=col, ls=ls, label=c)
    ax.set_xlabel("x / mm")
    ax.set_ylabel("y / mm")
    ax.set_zlabel("z / mm")
    ax.set_title(f"End-effector path ({sc}; cf. Fig. 9)")
    ax.legend()
    fig.savefig(os.path.join(out, "fig09_path.png"), dpi=110, bbox_inches="tight")
    plt.close(fig)

    # Fig. 10: joint angles.
    fig, axes = joint_grid(f"Joint angles ({sc}; cf. Fig. 10)")
    for j in range(1, 7):
        ax = axes[j - 1]
        t, qd = series(traj, sc, ctrls[0], j, "theta_d")
        ax.plot(t, qd, color="0.6", lw=3, label="θd")
        for c in ctrls:
            col, ls = STYLE.get(c, ("g", "-"))
            t, q = series(traj, sc, c, j, "theta")
            ax.plot(t, q, color=col, ls=ls, label=c)
        ax.set_title(f"joint {j}")
        ax.set_ylabel("θ / rad")
        if j > 3:
            ax.set_xlabel("t / s")
    axes[0].legend(fontsize=8)
    fig.savefig(os.path.join(out, "fig10_joints.png"), dpi=110, bbox_inches="tight")
    plt.close(fig)

    # Fig. 11: |error|, log scale.
    fig, axes = joint_grid(f"Joint error |θd − θ| ({sc}; cf. Fig. 11)")
    for j in range(1, 7):
        ax = axes[j - 1]
        for c in ctrls:
            col, ls = STYLE.get(c, ("g", "-"))
            t, e = series(traj, sc, c, j, "error")
            ax.semilogy(t, [max(abs(x), 1e-12) for x in e], color=col, ls=ls, label=c)
        ax.set_title(f"joint {j}")
        ax.set_ylabel("|e| / rad")
        if j > 3:
            ax.set_xlabel("t / s")
    axes[0].legend(fontsize=8)
    fig.savefig(os.path.join(out, "fig11_errors.png"), dpi=110, bbox_inches="tight")
    plt.close(fig)

    # Figs. 12-14: the gains over time.
    for col_name, number, label in (("kp", 12, "Kp"), ("ki", 13, "Ki"), ("kd", 14, "Kd")):
        fig, axes = joint_grid(f"{label} over time ({sc}; cf. Fig. {number}), paper units")
        for j in range(1, 7):
            ax = axes[j - 1]
            for c in ctrls:
                col, ls = STYLE.get(c, ("g", "-"))
                t, k = series(traj, sc, c, j, col_name)
                ax.plot(t, k, color=col, ls=ls, label=c)
            ax.set_title(f"joint {j}")
            ax.set_ylabel(label)
            if j > 3:
                ax.set_xlabel("t / s")
        axes[0].legend(fontsize=8)
        fig.savefig(os.path.join(out, f"fig{number}_{col_name}.png"), dpi=110, bbox_inches="tight")
        plt.close(fig)

    # Summary: mean over joints of ITAE and of max |e| after 1 s, per scenario and controller.
    scen = []
    for r in metrics:
        if r["scenario"] not in scen:
            scen.append(r["scenario"])
    all_ctrls = []
    for r in metrics:
        if r["controller"] not in all_ctrls:
            all_ctrls.append(r["controller"])
    itae = collections.defaultdict(list)
    for r in metrics:
        itae[(r["scenario"], r["controller"])].append(float(r["itae"]))
    late = collections.defaultdict(float)
    for r in traj:
        if float(r["t"]) >= 1.0 - 1e-9:
            key = (r["scenario"], r["controller"])
            late[key] = max(late[key], abs(float(r["error"])))
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(14, 5))
    width = 0.8 / max(len(all_ctrls), 1)
    for k, c in enumerate(all_ctrls):
        xs = [i + (k - (len(all_ctrls) - 1) / 2) * width for i in range(len(scen))]
        col = STYLE.get(c, ("g", "-"))[0]
        ax1.bar(xs, [sum(itae[(s, c)]) / max(len(itae[(s, c)]), 1) for s in scen], width,
                color=col, label=c)
        ax2.bar(xs, [late[(s, c)] for s in scen], width, color=col, label=c)
    for ax, title in ((ax1, "mean ITAE over joints / rad·s²"),
                      (ax2, "max |e| over joints for t ≥ 1 s / rad")):
        ax.set_xticks(range(len(scen)))
        ax.set_xticklabels(scen, rotation=20)
        ax.set_yscale("log")
        ax.set_title(title)
        ax.legend()
    fig.suptitle("Per-scenario summary")
    fig.savefig(os.path.join(out, "summary.png"), dpi=110, bbox_inches="tight")
    plt.close(fig)
    print(f"plot_sim: wrote figures to {out}/")


if __name__ == "__main__":
    main()
