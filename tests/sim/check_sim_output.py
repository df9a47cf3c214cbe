#!/usr/bin/python3
"""Checks one sim_ab output directory against the specification of its files.

usage: check_sim_output.py DIR

- trajectory.csv has the documented header; for the paper scenario one row per tick (t = 0, 0.05,
  ..., 5.0 inclusive) per joint (1..6) per controller; every number finite;
- the fuzzy controller's kp, ki, kd change over time, the fixed PID's do not;
- metrics.csv agrees with metrics recomputed here, independently, from trajectory.csv (the drive
  metrics from u and tau_nm) and endeffector.csv (the tool's path error).
Exits non-zero with a message on the first violation.
"""
import csv
import math
import sys

TRAJ_HEADER = ("scenario,controller,t,joint,theta_d,theta,error,error_rate,u,kp,ki,kd,tau_nm,"
               "omega_rad_s")
METRICS_HEADER = ("scenario,controller,joint,settling_time_s,overshoot_pct,max_abs_error_rad,"
                  "rms_error_rad,iae,itae,max_abs_error_after_1s_rad,faults,no_rule_ticks,"
                  "clamped_gain_ticks,reversals_pct,sign_changes_pct,saturated_pct,tau_rms_nm,"
                  "torque_variation_nm_per_s,tcp_error_max_mm,tcp_error_rms_mm,divergence_ticks,"
                  "joint_limit_ticks,limit_cycle_ticks")
TIP_HEADER = "scenario,controller,t,x_d,y_d,z_d,x,y,z"
DT = 0.05


def fail(msg):
    sys.exit(f"check_sim_output: {msg}")


def load(path, header):
    with open(path, newline="") as f:
        first = f.readline().strip()
        if first != header:
            fail(f"{path}: header is '{first}', expected '{header}'")
        return list(csv.DictReader(f, fieldnames=header.split(",")))


def sign(x):
    return (x > 0) - (x < 0)


def reversals(u):
    """Percentage of the K - 2 ticks on which a change above 1 % of u's range reverses the
    direction of the last such change."""
    if len(u) < 3:
        return 0.0
    h = 0.01 * (max(u) - min(u))
    dirs = [sign(b - a) for a, b in zip(u, u[1:]) if abs(b - a) > h]
    return 100.0 * sum(1 for a, b in zip(dirs, dirs[1:]) if a != b) / (len(u) - 2)


def sign_changes(u):
    """Percentage of the K - 1 ticks whose non-zero u has the opposite sign of the last non-zero u
    before it (a zero is no sign)."""
    if len(u) < 2:
        return 0.0
    nz = [sign(x) for x in u if x != 0]
    return 100.0 * sum(1 for a, b in zip(nz, nz[1:]) if a != b) / (len(u) - 1)


def drive(t, u, tau):
    return {
        "reversals_pct": reversals(u),
        "sign_changes_pct": sign_changes(u),
        "tau_rms_nm": math.sqrt(sum(x * x for x in tau) / len(tau)),
        "torque_variation_nm_per_s": (sum(abs(b - a) for a, b in zip(tau, tau[1:])) /
                                      (t[-1] - t[0]) if t[-1] > t[0] else 0.0),
    }


def metrics(t, theta_d, theta, e):
    travel = max(abs(theta_d[-1] - theta[0]), 1e-12)
    excursion = max(theta_d) - min(theta_d)
    closed = excursion > 0 and abs(theta_d[-1] - theta_d[0]) <= 0.01 * excursion
    base = max(excursion, travel) if closed else travel
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
        "overshoot_pct": 100.0 * max(0.0, max(-s * x for x in e)) / base,
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
        for k in ("t", "theta_d", "theta", "error", "error_rate", "u", "kp", "ki", "kd", "tau_nm",
                  "omega_rad_s"):
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
    tips = {}
    for r in load(f"{d}/endeffector.csv", TIP_HEADER):
        tips.setdefault((r["scenario"], r["controller"]), []).append(
            [float(r[k]) for k in ("x", "y", "z", "x_d", "y_d", "z_d")])
    seen = set()
    for m in met:
        key = (m["scenario"], m["controller"], int(m["joint"]))
        seen.add(key)
        if key not in groups:
            fail(f"metrics row {key} has no trajectory")
        rows = groups[key]
        t = [float(r["t"]) for r in rows]
        ref = metrics(t, [float(r["theta_d"]) for r in rows], [float(r["theta"]) for r in rows],
                      [float(r["error"]) for r in rows])
        ref.update(drive(t, [float(r["u"]) for r in rows], [float(r["tau_nm"]) for r in rows]))
        pos = tips[key[:2]]
        d = [1e3 * math.dist(p[:3], p[3:]) for p in pos]
        ref["tcp_error_max_mm"] = max(d)
        ref["tcp_error_rms_mm"] = math.sqrt(sum(x * x for x in d) / len(d))
        if not 0.0 <= float(m["saturated_pct"]) <= 100.0:
            fail(f"{key} saturated_pct {m['saturated_pct']}")
        for name, want in ref.items():
            got = float(m[name])
            if math.isinf(want) or math.isinf(got):
                if want != got:
                    fail(f"{key} {name}: metrics.csv {got}, recomputed {want}")
            elif abs(got - want) > 1e-9 * max(1.0, abs(want)) + (1e-9 if "tcp" in name else 0):
                fail(f"{key} {name}: metrics.csv {got}, recomputed {want}")
    if seen != set(groups):
        fail(f"metrics.csv covers {len(seen)} (scenario, controller, joint) triples, "
             f"trajectory.csv {len(groups)}")
    print(f"check_sim_output: {len(traj)} trajectory rows and {len(met)} metrics rows OK")


if __name__ == "__main__":
    main()
