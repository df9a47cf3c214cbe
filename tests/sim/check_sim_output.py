#!/usr/bin/python3
"""Checks one sim_ab output directory against the specification of its files.

usage: check_sim_output.py DIR

- trajectory.csv has the documented header; for the paper scenario one row per tick (t = 0, 0.05,
  ..., 5.0 inclusive) per joint (1..6) per controller; every number finite;
- the fuzzy controller's kp, ki, kd change over time, the fixed PID's do not;
- metrics.csv agrees with metrics recomputed here, independently, from trajectory.csv.
Exits non-zero with a message on the first violation.
"""
import csv
import math
import sys

TRAJ_HEADER = "scenario,controller,t,joint,theta_d,theta,error,error_rate,u,kp,ki,kd"
METRICS_HEADER = ("scenario,controller,joint,settling_time_s,overshoot_pct,max_abs_error_rad,"
                  "rms_error_rad,iae,itae,max_abs_error_after_1s_rad,faults,no_rule_ticks,"
                  "clamped_gain_ticks")
DT = 0.05


def fail(msg):
    sys.exit(f"check_sim_output: {msg}")


def load(path, header):
    with open(path, newline="") as f:
        first = f.readline().strip()
        if first != header:
            fail(f"{path}: header is '{first}', expected '{header}'")
        return list(csv.DictReader(f, fieldnames=header.split(",")))


def metrics(t, theta_d, theta, e):
    travel = max(abs(theta_d[-1] - theta[0]), 1e-12)
    band = 0.02 * travel
    s = 1.0 if e[0] > 0 else (-1.0 if e[0] < 0 else (-1.0 if theta_d[-1] >= theta_d[0] else 1.0))
    outside = [k for k, x in enumerate(e) if abs(x) > band]
    if not outside:
        settle = 0.0
    elif outside[-1] == len(e) - 1:
        settle = math.inf
    else:
        settle = t[outside[-1] + 1]
    return {
        "settling_time_s": settle,
        "overshoot_pct": 100.0 * max(0.0, max(-s * x for x in e)) / travel,
        "max_abs_error_rad": max(abs(x) for x in e),
        "rms_error_rad": math.sqrt(sum(x * x for x in e) / len(e)),
        "iae": sum(abs(x) * DT for x in e),
        "itae": sum(tk * abs(x) * DT for tk, x in zip(t, e)),
        "max_abs_error_after_1s_rad": max([abs(x) for tk, x in zip(t, e) if tk >= 1.0],
                                          default=0.0),
    }


def main():
    d = sys.argv[1]
    traj = load(f"{d}/trajectory.csv", TRAJ_HEADER)
    met = load(f"{d}/metrics.csv", METRICS_HEADER)
    groups = {}
    for r in traj:
        for k in ("t", "theta_d", "theta", "error", "error_rate", "u", "kp", "ki", "kd"):
            if not math.isfinite(float(r[k])):
                fail(f"non-finite {k} in row {r}")
        groups.setdefault((r["scenario"], r["controller"], int(r["joint"])), []).append(r)
    controllers = sorted({c for (_, c, _) in groups})
    for needed in ("pid", "fuzzy"):
        if needed not in controllers:
            fail(f"controller '{needed}' missing from trajectory.csv")
    for (scenario, controller, joint), rows in groups.items():
        if joint < 1 or joint > 6:
            fail(f"joint {joint} out of 1..6")
        t = [float(r["t"]) for r in rows]
        if scenario == "paper":
            if len(rows) != 101:
                fail(f"{scenario}/{controller}/joint {joint}: {len(rows)} rows, expected 101")
            for k, tk in enumerate(t):
                if abs(tk - k * DT) > 1e-9:
                    fail(f"{scenario}/{controller}/joint {joint}: t[{k}] = {tk}")
        for col in ("kp", "ki", "kd"):
            values = {float(r[col]) for r in rows}
            if controller.startswith("pid") and len(values) != 1:
                fail(f"{scenario}/{controller}/joint {joint}: fixed PID {col} changes")
        if controller == "fuzzy" and len({float(r["kp"]) for r in rows}) < 10:
            fail(f"{scenario}/fuzzy/joint {joint}: kp barely changes")
        for r in rows:
            if abs(float(r["error"]) - (float(r["theta_d"]) - float(r["theta"]))) > 1e-12:
                fail(f"error != theta_d - theta in {r}")
    if ("paper", "pid", 1) not in groups:
        fail("scenario 'paper' missing")
    seen = set()
    for m in met:
        key = (m["scenario"], m["controller"], int(m["joint"]))
        seen.add(key)
        if key not in groups:
            fail(f"metrics row {key} has no trajectory")
        rows = groups[key]
        ref = metrics([float(r["t"]) for r in rows], [float(r["theta_d"]) for r in rows],
                      [float(r["theta"]) for r in rows], [float(r["error"]) for r in rows])
        for name, want in ref.items():
            got = float(m[name])
            if math.isinf(want) or math.isinf(got):
                if want != got:
                    fail(f"{key} {name}: metrics.csv {got}, recomputed {want}")
            elif abs(got - want) > 1e-9 * max(1.0, abs(want)):
                fail(f"{key} {name}: metrics.csv {got}, recomputed {want}")
    if seen != set(groups):
        fail(f"metrics.csv covers {len(seen)} (scenario, controller, joint) triples, "
             f"trajectory.csv {len(groups)}")
    print(f"check_sim_output: {len(traj)} trajectory rows and {len(met)} metrics rows OK")


if __name__ == "__main__":
    main()
