#!/bin/sh
# Inputs that cannot be meant (issue 28, items 4, 6, 7 and 8), each as a new user would write it:
#   - an option its other options make meaningless is refused (exit 2) naming the option and why;
#   - a value that cannot be meant (degrees for radians, a path shorter than a tick, a URDF limit
#     in degrees, a joint that moves no inertia, stage budgets past the limit, a rule-table cell
#     beyond float) is refused with the file:line, joint or option and the value;
#   - legal input that is probably wrong (a payload above the arm's mass, a controller run on
#     another robot or path than it was tuned on, a URDF limit of 0) is run with a warning.
# A refusal writes nothing. Usage: check_unmeant_inputs.sh <fuzzypid> <sim_ab> <rt_loop> <source dir>
set -u
fuzzypid=$1
sim_ab=$2
rt_loop=$3
src=$4
ur5="$src/urdf/ur5_class.urdf"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
cases=0
fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}
# expect CODE PATTERN -- command...: the exit code, a part of stderr, and nothing at $work/out*
# after a refusal.
expect() {
  code=$1
  pattern=$2
  shift 3
  cases=$((cases + 1))
  rm -rf "$work"/out*
  "$@" >"$work/stdout" 2>"$work/err" </dev/null
  got=$?
  [ "$got" -eq "$code" ] || fail "$* exited $got, expected $code: $(cat "$work/err")"
  grep -q -- "$pattern" "$work/err" || fail "$*: no '$pattern' in: $(cat "$work/err")"
  if [ "$code" -ne 0 ]; then
    for f in "$work"/out*; do
      [ -e "$f" ] && fail "$*: wrote $f"
    done
  fi
}
row() { printf '%s\n' "$@"; }
J="t_s,q1_rad,q2_rad,q3_rad,q4_rad,q5_rad,q6_rad"
P="t_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad"
row "$J" "0,0,-1,1,0,0,0" "1,0,-1,1.2,0,0,0" >"$work/joint.csv"
row "$J" "0,0,-1,1,0,0,0" "0.01,0,-1,1.001,0,0,0" >"$work/short.csv"
row "$P" "0,0.4,0.1,0.3,180,0,0" "0.5,0.4,0.1,0.3,180,0,0" >"$work/degrees.csv"
# A refusal is immediate; a run that goes on (the stages' hours) is stopped and fails its case.
sim() { timeout 60 "$sim_ab" --quiet --out "$work/out" "$@"; }
rt() { timeout 60 "$rt_loop" --period-ms 0 "$@"; }
tune() {
  timeout 60 "$fuzzypid" tune --conditions "$src/tuning/robust.toml" --out "$work/out.toml" --budget 40 \
    --population 20 --quiet "$@"
}

# 1. Options that do nothing in their combination.
expect 2 "--ik-seed applies only to a Cartesian path file; without --path the built-in line" -- \
  sim --ik-seed 0,0,0,0,0,0
expect 2 "--ik-seed applies only to a Cartesian path file; without --path" -- \
  rt --ik-seed 0,0,0,0,0,0
expect 1 "--ik-seed (condition key ik_seed) applies only to a Cartesian path file; $work/joint.csv is a joint path" -- \
  sim --urdf "$ur5" --path "$work/joint.csv" --ik-seed 0,-1,1,0,0,0
expect 2 "--overshoot-bound applies only to --sweep" -- sim --overshoot-bound 10
expect 2 "--itae-ratio applies only to --sweep" -- sim --itae-ratio 2
expect 2 "--scenario does nothing with --list" -- "$sim_ab" --list --scenario noise
expect 2 "--require-rt applies only to --fifo, --lock-memory or --cpu" -- rt --ticks 2 --require-rt
expect 2 "--loop applies only to --ticks beyond one pass; without --ticks" -- rt --loop
expect 2 "--loop applies only to --ticks beyond one pass; --ticks 50 is within the path's 101" -- \
  rt --loop --ticks 50
expect 2 "--max-overruns applies only to a timed loop; --period-ms 0 runs free" -- \
  rt --ticks 2 --max-overruns 3
expect 2 "--seed applies only to a run with measurement noise; no selected condition has any" -- \
  sim --seed 7
expect 2 "--strict-rules applies only to a controller with a supervisor; every --controller is a pid" -- \
  sim --strict-rules --controller "$src/controllers/tuned_pid.toml"
expect 2 "--strict-rules applies only to a controller with a supervisor; --controller pid has none" -- \
  rt --ticks 2 --strict-rules --controller pid
expect 2 "--strict-rules applies only to a controller with a supervisor; .*tuned_pid.toml is a pid" -- \
  rt --ticks 2 --strict-rules --controller "$src/controllers/tuned_pid.toml"
for option in "--symmetry odd" "--partition fixed" "--smoothness 1" "--monotone 1" \
  "--unvisited free" "--visit-threshold 0.01" "--cell-log10 2"; do
  # shellcheck disable=SC2086
  expect 2 "${option%% *} applies only to a fuzzy-rules search (--family or a --stages stage); --family is pid" -- \
    tune --family pid $option
done
expect 2 "--symmetry applies only to a fuzzy-rules search.*; the stages are pid, scheduled" -- \
  tune --stages pid:20,scheduled:20 --symmetry none
expect 2 "--visit-threshold applies only to --unvisited seed; --unvisited free searches every cell" -- \
  tune --family fuzzy-rules --unvisited free --visit-threshold 0.01
rules="$src/tests/cli/data/fuzzy_rules.toml"
expect 2 "--surface-points applies only to --surface; no --surface CSV is written" -- \
  "$fuzzypid" export-rules "$rules" --out "$work/out.fll" --surface-points 9
expect 2 "--format applies only to --out; no rule file is written without --out" -- \
  "$fuzzypid" export-rules "$rules" --surface "$work/out.csv" --format fcl

# 2. Values that cannot be meant.
expect 1 "degrees.csv:2: roll_rad 180 is beyond one turn.*radians" -- \
  sim --urdf "$ur5" --path "$work/degrees.csv"
expect 1 "short.csv: the path lasts 0.01 s, less than one tick (0.05 s)" -- \
  sim --urdf "$ur5" --path "$work/short.csv"
expect 1 "short.csv: the path lasts 0.01 s, less than one tick" -- \
  rt --urdf "$ur5" --path "$work/short.csv"
sed '0,/lower="-3.14159265" upper="3.14159265"/s//lower="-180" upper="180"/' "$ur5" >"$work/degrees.urdf"
expect 1 "joint 'elbow_joint': <limit> lower=\"-180\" rad is beyond two turns" -- \
  sim --urdf "$work/degrees.urdf" --path "$work/joint.csv"
awk '/<link name="wrist_3_link">/ { print "  <link name=\"wrist_3_link\"/>"; skip = 1; next }
     skip && /<\/link>/ { skip = 0; next } !skip' "$ur5" >"$work/no_inertial.urdf"
expect 1 "no inertia moves with joint 6 ('wrist_3_joint'): link 'wrist_3_link'" -- \
  sim --urdf "$work/no_inertial.urdf" --path "$work/joint.csv"
expect 2 "--stages: the budgets sum to 150000000 evaluations, above the limit 100000000" -- \
  timeout 60 "$fuzzypid" tune --conditions "$src/tuning/robust.toml" --out "$work/out.toml" \
  --quiet --stages pid:100000000,scheduled:50000000
# The second cell of the first row of the rule table's kp, whatever the tuner put there.
awk 'row { sub(/^  \[[^,]*, [^,]*,/, "  [1.0, 1e300,"); row = 0 } /^kp = \[$/ { row = 1 } { print }' \
  "$src/controllers/tuned_fuzzy_rules.toml" >"$work/huge_cell.toml"
grep -q '^  \[1.0, 1e300,' "$work/huge_cell.toml" || { echo "FAIL: no cell replaced"; exit 1; }
expect 1 "rule_table kp\[0\]\[1\] (e NB, ec NM) is 1.0000000000000001e+300" -- \
  "$fuzzypid" export-header "$work/huge_cell.toml" --out "$work/out.hpp"
expect 1 "rule table Kp cell \[0\]\[1\] (e NB, ec NM) is 1e+300, beyond the float range" -- \
  "$fuzzypid" export-rules "$work/huge_cell.toml" --out "$work/out.fll"

# 3. Records that lie, and legal input that is probably wrong: warnings, the run goes on.
sed 's/fnv1a64 = "a7e492482337c9be"/fnv1a64 = "not-a-hash"/' \
  "$src/controllers/ur5_class_tuned_pid.toml" >"$work/bad_hash.toml"
expect 1 "bad_hash.toml:[0-9]*:[0-9]*: trained_on fnv1a64 \"not-a-hash\" is not a 64-bit FNV-1a hash: expected 16 lower-case hex digits" -- \
  sim --controller "$work/bad_hash.toml"
expect 0 "warning: controller $src/controllers/ur5_class_tuned_pid.toml runs on another robot or path than it was tuned on: urdf: trained on \.\./urdf/ur5_class.urdf" -- \
  sim --controller "$src/controllers/ur5_class_tuned_pid.toml" --allow-faults
grep -q "path: trained on \.\./paths/ur5_deburring_contour.csv (fnv1a64 294f2a043cf958bc), run on the built-in line A -> B" "$work/err" ||
  fail "the path difference is not named: $(cat "$work/err")"
expect 0 "warning: controller .*ur5_class_tuned_pid.toml runs on another robot or path than it was tuned on: path: trained on \.\./paths/ur5_deburring_contour.csv" -- \
  rt --ticks 2 --urdf "$ur5" --path "$work/joint.csv" --controller "$src/controllers/ur5_class_tuned_pid.toml"
grep -q "urdf: trained on" "$work/err" && fail "the same URDF is named as a difference: $(cat "$work/err")"
# On its own robot and path, no warning (it rings on its torque limits there: a limit-cycle
# fault, accepted here; docs/margins.md).
sim --urdf "$ur5" --path "$src/paths/ur5_deburring_contour.csv" --tick-ms 10 --allow-faults \
  --controller "$src/controllers/ur5_class_tuned_pid.toml" 2>"$work/err" ||
  fail "ur5 controller on its robot: $(cat "$work/err")"
grep -q "warning" "$work/err" && fail "warning on the robot it was tuned on: $(cat "$work/err")"
rm -rf "$work/out"
expect 0 "warning: condition paper: payload 500 kg is above the arm's own moving mass 365 kg" -- \
  "$sim_ab" --quiet --out "$work/run" --payload-kg 500
expect 0 "warning: condition paper: payload 500 kg is above the arm's own moving mass 365 kg" -- \
  rt --ticks 2 --payload-kg 500
sed '0,/effort="28" velocity="3.15"/s//effort="0" velocity="0"/' "$ur5" >"$work/unlimited.urdf"
expect 0 "note: $work/unlimited.urdf: joint 'wrist_1_joint': <limit> effort=\"0\" means no limit" -- \
  "$sim_ab" --quiet --out "$work/run" --urdf "$work/unlimited.urdf" --path "$work/joint.csv" --allow-faults
grep -q "joint 'wrist_1_joint': <limit> velocity=\"0\" means no limit" "$work/err" ||
  fail "velocity=\"0\" not noted: $(cat "$work/err")"
[ "$(grep -c "means no limit" "$work/err")" -eq 2 ] || fail "not once per joint: $(cat "$work/err")"
# A tuned file records the condition file it read (its hash); run on that file after an edit, it
# is warned about, and not before (a tune once read a half-edited file, and nothing showed it).
cp "$src/tuning/robust.toml" "$work/conds.toml"
timeout 60 "$fuzzypid" tune --family pid --conditions "$work/conds.toml" --out "$work/tuned.toml" --budget 40 \
  --population 20 --quiet 2>"$work/err" || fail "tune on a copy: $(cat "$work/err")"
grep -q '{ kind = "conditions", file = "conds.toml", fnv1a64 = "[0-9a-f]\{16\}" }' \
  "$work/tuned.toml" || fail "no conditions entry: $(grep -A3 trained_on "$work/tuned.toml")"
"$sim_ab" --quiet --out "$work/run" --conditions "$work/conds.toml" --set held-out \
  --controller "$work/tuned.toml" --allow-faults 2>"$work/err" || fail "run: $(cat "$work/err")"
grep -q "has changed since" "$work/err" && fail "warned before any edit: $(cat "$work/err")"
echo "# edited after the tune" >>"$work/conds.toml"
expect 0 "warning: controller $work/tuned.toml was tuned on conds.toml (fnv1a64 [0-9a-f]*), which has changed since (now [0-9a-f]*)" -- \
  "$sim_ab" --quiet --out "$work/run" --conditions "$work/conds.toml" --set held-out \
  --controller "$work/tuned.toml" --allow-faults
# certify reads the same record: its margins over those sets hold for the content the tune read.
expect 0 "warning: controller $work/tuned.toml was tuned on conds.toml (fnv1a64 [0-9a-f]*), which has changed since" -- \
  "$fuzzypid" certify "$work/tuned.toml" --conditions "$work/conds.toml" --set held-out --grid 3

[ "$failures" -eq 0 ] || {
  echo "$failures of $cases cases failed" >&2
  exit 1
}
echo "all $cases unmeant-input cases behave"
