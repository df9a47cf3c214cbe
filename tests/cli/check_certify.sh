#!/bin/sh
# certify: a fixed PID with positive margins is certified (exit 0), so is a gain schedule whose box
# has a common Lyapunov function; the paper's fuzzy PID is not (exit 1: its Ki reaches 0), nor an
# unstable PID (exit 1); the paper's PD-like gains give
# the closed-form gain margin 2 / (Kd h) of a double integrator under ZOH; an extra delay lowers the
# delay margin by itself; --json is the same twice; bad usage exits 2 naming the option.
# Usage: check_certify.sh <fuzzypid> <source dir> <python3>
set -u
fuzzypid=$1
src=$2
python=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
# expect CODE PATTERN -- command...: exit code and a line of stdout or stderr matching PATTERN.
expect() {
  code=$1
  pattern=$2
  shift 3
  "$@" >"$work/out" 2>&1
  got=$?
  [ "$got" -eq "$code" ] || { cat "$work/out" >&2; fail "exit $got, expected $code: $*"; }
  grep -q -- "$pattern" "$work/out" || { cat "$work/out" >&2; fail "no '$pattern': $*"; }
}

pid="$src/controllers/paper_pid.toml"
expect 0 "^certified (linear, no saturation; gains may change every tick)$" -- "$fuzzypid" certify "$pid"
expect 0 "^certified (linear, no saturation; gains may change every tick)$" -- \
  "$fuzzypid" certify "$src/tests/sim/data/certified_schedule.toml" --grid 5
expect 1 "^not certified (joint 1: Ki reaches 0 inside the box" -- \
  "$fuzzypid" certify "$src/controllers/paper_fuzzy.toml" --grid 5

# Kd per tick 1000 at a 50 ms tick: Kd h = 2.5 > 2, beyond the double integrator's boundary.
sed 's/^kd = .*/kd = 1000.0/' "$pid" >"$work/unstable.toml"
grep -q '^kd = 1000.0$' "$work/unstable.toml" || fail "kd not replaced"
expect 1 "^not certified (unstable at frozen gains)$" -- "$fuzzypid" certify "$work/unstable.toml"

# Deterministic JSON.
"$fuzzypid" certify "$pid" --json >"$work/a.json" || fail "json run 1"
"$fuzzypid" certify "$pid" --json >"$work/b.json" || fail "json run 2"
cmp -s "$work/a.json" "$work/b.json" || fail "--json differs between two runs"
"$fuzzypid" certify "$pid" --json --delay-ms 50 >"$work/d.json" || fail "json with delay"
"$python" - "$work/a.json" "$work/d.json" <<'PY' || fail "JSON values"
import json, math, sys
a = json.load(open(sys.argv[1]))
d = json.load(open(sys.argv[2]))
assert a["certified"] is True and a["family"] == "pid", a
assert "no saturation" in a["assumptions"], a
for j in a["joints"]:
    for key in ("gain_margin_db", "phase_margin_deg", "delay_margin_ms", "disk_margin"):
        assert isinstance(j[key], float) and j[key] > 0, (key, j)
    assert j["inertia_kgm2"][0] <= j["inertia_kgm2"][1]
    # A fixed PID: a box of one point, certified with a contraction below 1.
    assert j["certified"] is True, j
    assert j["gain_box"]["kp"] == [4.0, 4.0] and j["gain_box"]["kd"] == [5.0, 5.0], j
    assert j["lyapunov"]["certified"] is True and 0 < j["lyapunov"]["contraction_per_tick"] < 1, j
# Joint 6 (constant inertia = J^): the PD-dominated loop's margin at z = -1 is 2 / (Kd h) with
# Kd = 100 per tick = 5 s at h = 0.05 s, plus the integral's tiny share (Ki h z / (z - 1) = Ki h / 2).
kp, ki, kd, h = 4.0, 0.001 / 0.05, 100.0 * 0.05, 0.05
l_nyquist = -kd * h / 2 + 0.0  # P and I terms vanish at z = -1 (Ptheta(-1) = 0)
gm = 20 * math.log10(-1 / l_nyquist)
assert abs(a["joints"][5]["gain_margin_db"] - gm) < 1e-6, (a["joints"][5]["gain_margin_db"], gm)
# One more tick of delay leaves |L| alone and takes w_c * 50 ms of phase: 50 ms less margin.
for ja, jd in zip(a["joints"], d["joints"]):
    assert abs(ja["delay_margin_ms"] - jd["delay_margin_ms"] - 50.0) < 1e-6, (ja, jd)
assert d["delay_ms"] == 50.0
PY
# A fractional delay (12 ms at a 50 ms tick) uses up as much of the exact delay margin.
"$fuzzypid" certify "$pid" --json --delay-ms 12 >"$work/f.json" || fail "json with 12 ms"
"$python" - "$work/a.json" "$work/f.json" <<'PY' || fail "fractional delay"
import json, sys
a = json.load(open(sys.argv[1]))
f = json.load(open(sys.argv[2]))
for ja, jf in zip(a["joints"], f["joints"]):
    assert abs(ja["delay_margin_exact_ms"] - jf["delay_margin_exact_ms"] - 12.0) < 1e-6, (ja, jf)
    assert 0 < ja["delay_margin_exact_ms"] <= 50.0 * ja["delay_margin_ticks"]
PY

# Condition sets: the held-out set's inertia range covers the default condition's.
"$fuzzypid" certify "$src/controllers/tuned_pid.toml" --json \
  --conditions "$src/tuning/robust.toml" --set training >"$work/set.json"
[ $? -le 1 ] || fail "certify on a set"
grep -q '"conditions": 14' "$work/set.json" || fail "training set has 14 conditions"

# An elastic gear is in the loop the margins are of (the drive measures the motor): a 10 Hz gear
# (the tick's Nyquist rate) behind a 30 Hz current loop leaves joint 1 of the drive re-tune's PID
# (the fixed PID shipped until trial 10) unstable at its frozen gains, as the simulation rings
# there; a 40 Hz one is certified.
expect 1 "^1 .* NO$" -- "$fuzzypid" certify "$src/tests/sim/data/drive_retune_pid.toml" \
  --joint-resonance-hz 10 --joint-damping-ratio 0.05 --torque-bandwidth-hz 30
expect 0 "^certified" -- "$fuzzypid" certify "$src/tests/sim/data/drive_retune_pid.toml" \
  --joint-resonance-hz 40 --joint-damping-ratio 0.05 --torque-bandwidth-hz 30

# Usage errors: exit 2 naming the option or file.
expect 2 "^--set: " -- "$fuzzypid" certify "$pid" --set held-out
expect 2 "has no set 'nope'" -- "$fuzzypid" certify "$pid" --conditions "$src/tuning/robust.toml" \
  --set nope
expect 2 "^--conditions: " -- "$fuzzypid" certify "$pid" --conditions "$src/tuning/robust.toml" \
  --urdf "$src/urdf/ur5_class.urdf"
expect 2 "no-such.toml" -- "$fuzzypid" certify "$work/no-such.toml"
expect 2 "delay-ms" -- "$fuzzypid" certify "$pid" --delay-ms -5
expect 2 "grid" -- "$fuzzypid" certify "$pid" --grid 2
expect 2 "controller is required" -- "$fuzzypid" certify
# Per-tick gains run at another tick are converted, and standard error says so.
expect 0 "note: .*paper_pid.toml's per-tick gains refer to a 0.05 s tick" -- \
  "$fuzzypid" certify "$pid" --tick-ms 10
# The shipped fixed PID keeps the disk margin docs/margins.md gives it over the drive plant's
# held-out set, gear and delay modelled (0.397, joint 1); the PID shipped before it had 0.0013.
"$fuzzypid" certify "$src/controllers/tuned_pid.toml" --json \
  --conditions "$src/tuning/robust_drive.toml" --set held-out >"$work/drive.json" ||
  fail "the shipped PID is not certified over the drive's held-out set"
"$python" - "$work/drive.json" <<'PY' || fail "the shipped PID's documented disk margin"
import json, sys
d = json.load(open(sys.argv[1]))
worst = min(j["disk_margin"] for j in d["joints"])
assert abs(worst - 0.397) < 1e-3, worst
PY
echo "certify: ok"
