#!/usr/bin/env python3
"""The plant's default step has converged where it is stiff: sim_ab with the default step against
the same run with --plant-step-ms ten or more times finer, largest |theta - theta_fine| over every
tick, joint and controller below 1e-6 rad (docs/your_robot.md, "What real joints have").
Usage: check_step_convergence.py <sim_ab> <work dir>"""
import csv
import os
import subprocess
import sys

sim_ab, work = sys.argv[1], sys.argv[2]
CASES = [
    ("friction-100-coupled", ["--friction", "100", "--dynamics", "coupled", "--gravity"], "0.1"),
    ("friction-100-decoupled", ["--friction", "100"], "0.1"),
    ("gear-20hz-coupled", ["--joint-resonance-hz", "20", "--joint-damping-ratio", "0.05",
                           "--dynamics", "coupled", "--gravity"], "0.05"),
    ("delay-lag", ["--delay-ms", "25", "--torque-bandwidth-hz", "100"], "0.05"),
]


def thetas(out):
    with open(os.path.join(out, "trajectory.csv"), newline="") as f:
        return [float(r["theta"]) for r in csv.DictReader(f)]


failures = 0
for name, args, fine in CASES:
    runs = []
    for extra in ([], ["--plant-step-ms", fine]):
        out = os.path.join(work, "convergence-" + name + ("-fine" if extra else ""))
        # The paper's PID cannot hold the ER50 up against gravity (joint 2 passes the 1 rad fault
        # bound); the trajectories are compared all the same, so faults do not fail the run.
        subprocess.run([sim_ab, "--quiet", "--allow-faults", "--out", out] + args + extra,
                       check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        runs.append(thetas(out))
    if len(runs[0]) != len(runs[1]) or not runs[0]:
        print(f"FAIL {name}: {len(runs[0])} against {len(runs[1])} rows")
        failures += 1
        continue
    worst = max(abs(a - b) for a, b in zip(*runs))
    print(f"{name}: max |theta - theta_fine| = {worst:.2e} rad (--plant-step-ms {fine})")
    if not worst < 1e-6:
        failures += 1
sys.exit(1 if failures else 0)
