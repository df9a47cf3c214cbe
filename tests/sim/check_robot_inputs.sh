#!/bin/sh
# Bad robot, path and plant input to sim_ab and rt_loop: each case exits with its exact code (2 a
# usage error, 1 a bad file or an impossible path), says what is wrong (the file and row where
# there is one) and writes nothing.
# Usage: check_robot_inputs.sh <sim_ab> <rt_loop> <source dir>
set -u
sim_ab=$1
rt_loop=$2
src=$3
ur5="$src/urdf/ur5_class.urdf"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}
# expect CODE PATTERN -- command...: the exit code, a part of stderr, and no output directory.
expect() {
  code=$1
  pattern=$2
  shift 3
  rm -rf "$work/out"
  "$@" >"$work/stdout" 2>"$work/err" </dev/null
  got=$?
  [ "$got" -eq "$code" ] || fail "$* exited $got, expected $code: $(cat "$work/err")"
  grep -q -- "$pattern" "$work/err" || fail "$*: no '$pattern' in: $(cat "$work/err")"
  [ ! -e "$work/out" ] || fail "$*: wrote $work/out"
}
row() { printf '%s\n' "$@"; }
J="t_s,q1_rad,q2_rad,q3_rad,q4_rad,q5_rad,q6_rad"
P="t_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad"

row "$J" "0,0,-1,1,0,0,0" "0.5,0,-1,1,0,0,0" "0.5,0,-1,1,0,0,0.1" >"$work/flat_time.csv"
row "$J" "0,0,-1,1,0,0,0" "0.5,0,nan,1,0,0,0" >"$work/nan.csv"
row "$J" "0,0,-1,1,0,0,0" >"$work/one_row.csv"
row "t,a,b,c,d,e,f" "0,0,-1,1,0,0,0" "1,0,-1,1,0,0,0" >"$work/header.csv"
row "$J" "0,0,-1,1,0,0,0" "1,0,-1,3.5,0,0,0" >"$work/limits.csv"
row "$J" "0,0,-1,1,0,0,0" "0.1,0,-1,1.5,0,0,0" >"$work/fast.csv"
row "$P" "0,0.4,0.1,0.3,3.1,0,0" "0.5,3.0,0.1,0.3,3.1,0,0" >"$work/far.csv"
row "$J" "0,0,-1,1,0,0,0" "1,0,-1,1.2,0,0,0" >"$work/good.csv"

run() { "$sim_ab" --quiet --out "$work/out" "$@"; }
expect 1 "flat_time.csv:4: time 0.5 s does not increase" -- run --urdf "$ur5" --path "$work/flat_time.csv"
expect 1 "nan.csv:3: field 3 is not finite" -- run --urdf "$ur5" --path "$work/nan.csv"
expect 1 "one_row.csv: a path needs at least two rows, found 1" -- run --urdf "$ur5" --path "$work/one_row.csv"
expect 1 "header.csv:1: unknown header" -- run --urdf "$ur5" --path "$work/header.csv"
expect 1 "limits.csv:3: row at t = 1 s: joint 3 at 3.5 rad is outside its URDF limits" -- run --urdf "$ur5" --path "$work/limits.csv"
expect 1 "fast.csv:3: row at t = 0.1 s: joint 3 moves at 5 rad/s" -- run --urdf "$ur5" --path "$work/fast.csv"
expect 1 "far.csv:3: row at t = 0.5 s: pose (3, 0.1, 0.3) m" -- run --urdf "$ur5" --path "$work/far.csv"
expect 1 "refused it: no_convergence" -- run --urdf "$ur5" --path "$work/far.csv"
expect 1 "cannot open '$work/missing.csv'" -- run --urdf "$ur5" --path "$work/missing.csv"
expect 1 "five_joints.urdf" -- run --urdf "$src/tests/robot/data/five_joints.urdf" --path "$work/good.csv"
expect 1 "needs its own path (--path FILE)" -- run --urdf "$ur5"
expect 2 "payload-kg" -- run --payload-kg -1
expect 2 "--armature: expected 6 comma-separated numbers" -- run --armature 1,2,3
expect 2 "--gravity needs --dynamics coupled" -- run --gravity
expect 2 "--gravity needs --dynamics coupled" -- run --dynamics decoupled --gravity
expect 2 "--dynamics" -- run --dynamics rigid
expect 2 "--tick-ms" -- run --tick-ms 0
expect 2 "--path replaces it" -- run --path "$work/good.csv" --start 1,2,3
expect 2 "--start: values must be within ±1e6 mm" -- run --start 2e6,0,0
expect 2 "--end: values must be within ±1e6 mm" -- run --end 0,0,-1.3e48
expect 2 "the robot options apply without it" -- run --conditions "$src/tuning/robust.toml" --urdf "$ur5"
expect 2 "--gravity needs --dynamics coupled" -- "$rt_loop" --period-ms 0 --gravity
expect 2 "--tick-ms and --dt both set the controller period" -- "$rt_loop" --tick-ms 10 --dt 0.01
expect 1 "limits.csv:3" -- "$rt_loop" --period-ms 0 --urdf "$ur5" --path "$work/limits.csv"
# What real joints have: 0 (off, or the default: the message says which) or within the range, in
# sim_ab, rt_loop and condition files.
expect 2 "--plant-step-ms: expected 0 (the default step) or a number within 0.001 .. 1000: -1" -- run --plant-step-ms -1
expect 2 "--plant-step-ms: expected 0 (the default step) or a number within 0.001 .. 1000: nan" -- run --plant-step-ms nan
expect 2 "--plant-step-ms" -- "$rt_loop" --period-ms 0 --plant-step-ms 1e9
expect 2 "--delay-ms: expected 0 (none) or a number within 0 .. 1000: -5" -- run --delay-ms -5
expect 2 "--torque-bandwidth-hz: expected 0 (ideal) or a number within 0.1 .. 100000: nan" -- run --torque-bandwidth-hz nan
expect 2 "--encoder-counts: expected 0 (exact) or an integer within 4 .. 1e+12: 1.5" -- run --encoder-counts 1.5
expect 2 "--coulomb-nm: values must be within 0 .. 1e+06: 1,2,3,4,5,-6" -- run --coulomb-nm 1,2,3,4,5,-6
expect 2 "--armature: values must be within 0 .. 1e+06: 1,1,1,1,1,2e6" -- run --armature 1,1,1,1,1,2e6
expect 2 "--stribeck-nm: expected one number or 6 comma-separated: 1,2" -- run --stribeck-nm 1,2
expect 2 "--stribeck-velocity: expected 0 (the plant's default) or a number within 1e-05 .. 100: -1" -- "$rt_loop" --period-ms 0 --stribeck-velocity -1
expect 2 "delay_ms must be at most 60 ticks (60 ms at this tick)" -- run --tick-ms 1 --delay-ms 61
expect 2 "--joint-resonance-hz: values must be within 0 .. 10000: -1" -- run --joint-resonance-hz -1
expect 2 "--joint-damping-ratio" -- "$rt_loop" --period-ms 0 --joint-damping-ratio nan
expect 1 "joint_resonance_hz needs an armature > 0 on joint 2" -- run --joint-resonance-hz 20 --armature 1,0,1,1,1,1
expect 2 "--backlash-rad: expected 0 (none) or a number within 0 .. 1: 2" -- run --backlash-rad 2
expect 2 "backlash_rad needs an elastic gear (joint_resonance_hz > 0)" -- run --backlash-rad 0.001
row "[sets.s]" "conditions = [ { name = \"c\", plant_step_ms = -1.0 } ]" >"$work/bad_step.toml"
# A gear on an arm without armature, in the second of two conditions: refused before the first runs.
row "[sets.s]" "urdf = \"$ur5\"" "path = \"$work/good.csv\"" \
  "conditions = [ { name = \"rigid\" }, { name = \"geared\", joint_resonance_hz = 12.0 } ]" \
  >"$work/gear.toml"
expect 1 "condition geared: joint_resonance_hz needs an armature > 0 on joint 1" -- \
  run --conditions "$work/gear.toml" --allow-faults
grep -q "rigid" "$work/err" && fail "gear.toml: a condition ran before the refusal: $(cat "$work/err")"
expect 1 "bad_step.toml:2:46: 'plant_step_ms' must be 0 (the default step)" -- run --conditions "$work/bad_step.toml"

# And the good path runs, with the robot it used stated on stderr.
run --urdf "$ur5" --path "$work/good.csv" --tick-ms 10 --allow-faults 2>"$work/err" ||
  fail "good path: $(cat "$work/err")"
rm -rf "$work/out"
"$sim_ab" --out "$work/out" --urdf "$ur5" --path "$work/good.csv" 2>"$work/err" >/dev/null
grep -q "armature 0,0,0,0,0,0 kg·m²" "$work/err" || fail "armature not stated: $(cat "$work/err")"
grep -q "^armature_kgm2=0,0,0,0,0,0$" "$work/out/settings.txt" || fail "settings: armature"
grep -q "^path=$work/good.csv fnv1a64=[0-9a-f]\{16\}$" "$work/out/settings.txt" ||
  fail "settings: path"

[ "$failures" -eq 0 ] || exit 1
echo "all robot-input cases behave"
