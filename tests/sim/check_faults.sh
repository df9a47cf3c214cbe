#!/bin/sh
# Faults are faults: a run in which a joint's |error| passes --divergence (default 1 rad) or a
# joint leaves its URDF limits is counted in metrics.csv `faults` (and per joint in
# divergence_ticks, joint_limit_ticks), named on stderr with controller, condition, joint, time
# and value, and exits 1 unless --allow-faults -- in sim_ab's runs and sweeps and in rt_loop.
# The paper's PID with its gains x10 (tests/sim/data/paper_pid_x10.toml) diverges on the paper
# scenario; the paper's PID beside it does not.
# Usage: check_faults.sh <sim_ab> <rt_loop> <source dir>
set -u
sim_ab=$1
rt_loop=$2
src=$3
x10=$src/tests/sim/data/paper_pid_x10.toml
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
# Column N of metrics.csv summed over the rows of controller C.
column_sum() { awk -F, -v c="$2" -v n="$3" 'NR > 1 && $2 == c { s += $n } END { print s + 0 }' "$1"; }
col() { head -1 "$1" | tr ',' '\n' | grep -nx "$2" | cut -d: -f1; }

"$sim_ab" --quiet --controller "$x10" --controller "$src/controllers/paper_pid.toml" \
  --out "$work/x10" 2>"$work/err"
[ $? -eq 1 ] || fail "sim_ab with a diverging controller did not exit 1: $(cat "$work/err")"
grep -Eq "^sim_ab: fault: paper_pid_x10 on paper: joint [1-6]: \|error\| [0-9.]+ rad > 1 rad at t = [0-9.]+ s \(first of [0-9]+ ticks\)$" \
  "$work/err" || fail "no fault named: $(cat "$work/err")"
grep -q "fault: paper_pid on" "$work/err" && fail "the paper PID named as faulting"
grep -q "run(s) with faults (metrics.csv .faults.; --allow-faults accepts them)" "$work/err" ||
  fail "no summary line: $(cat "$work/err")"
m=$work/x10/metrics.csv
[ "$(column_sum "$m" paper_pid_x10 "$(col "$m" faults)")" -gt 0 ] || fail "faults is 0"
[ "$(column_sum "$m" paper_pid_x10 "$(col "$m" divergence_ticks)")" -gt 0 ] ||
  fail "divergence_ticks is 0"
[ "$(column_sum "$m" paper_pid "$(col "$m" faults)")" -eq 0 ] || fail "paper_pid faults"

"$sim_ab" --quiet --allow-faults --controller "$x10" --out "$work/allowed" 2>"$work/err" ||
  fail "--allow-faults did not exit 0: $(cat "$work/err")"
grep -q "^sim_ab: fault: paper_pid_x10 on paper: joint" "$work/err" || fail "allowed: not named"
[ "$(column_sum "$work/allowed/metrics.csv" paper_pid_x10 11)" -gt 0 ] || fail "allowed: faults 0"
# The bound is the option's: 100 rad is never passed. The loop still rings on its torque limits
# at the Nyquist rate: a limit cycle, a fault whatever the bound (exit 1, named).
"$sim_ab" --quiet --divergence 100 --controller "$x10" --out "$work/loose" 2>"$work/err"
[ $? -eq 1 ] || fail "--divergence 100: the limit cycle did not fail the run: $(cat "$work/err")"
grep -q "^sim_ab: fault: paper_pid_x10 on paper: joint [0-9]: limit cycle: torque on its limits" \
  "$work/err" || fail "loose: the limit cycle is not named: $(cat "$work/err")"
m="$work/loose/metrics.csv"
[ "$(column_sum "$m" paper_pid_x10 "$(col "$m" divergence_ticks)")" -eq 0 ] ||
  fail "loose: divergence_ticks"
[ "$(column_sum "$m" paper_pid_x10 "$(col "$m" limit_cycle_ticks)")" -gt 0 ] ||
  fail "loose: limit_cycle_ticks is 0"
grep -q "^divergence_rad=100$" "$work/loose/settings.txt" || fail "settings.txt divergence_rad"

# A sweep: the faulting runs are named and make it exit 1, unless --allow-faults.
"$sim_ab" --quiet --sweep payload-scale=0.5:1:2 --controller "$x10" --out "$work/sweep" \
  2>"$work/err"
[ $? -eq 1 ] || fail "sweep with faults did not exit 1"
grep -q "^sim_ab: fault: paper_pid_x10 on payload-scale=" "$work/err" || fail "sweep: $(cat "$work/err")"
"$sim_ab" --quiet --allow-faults --sweep payload-scale=0.5:1:2 --controller "$x10" \
  --out "$work/sweep2" 2>/dev/null || fail "sweep --allow-faults did not exit 0"

"$rt_loop" --period-ms 0 --controller "$x10" >"$work/out" 2>"$work/err"
[ $? -eq 1 ] || fail "rt_loop with a diverging controller did not exit 1"
grep -Eq "^tracking_fault_ticks: [1-9][0-9]* ticks" "$work/out" || fail "rt_loop: $(cat "$work/out")"
grep -Eq "^rt_loop: fault: joint [1-6]: \|error\| [0-9.]+ rad > 1 rad at t = " "$work/err" ||
  fail "rt_loop: not named: $(cat "$work/err")"
"$rt_loop" --period-ms 0 --allow-faults --controller "$x10" >/dev/null 2>&1 ||
  fail "rt_loop --allow-faults did not exit 0"
"$rt_loop" --period-ms 0 --controller "$src/controllers/paper_pid.toml" >"$work/out" 2>&1 ||
  fail "rt_loop paper_pid: $(cat "$work/out")"
grep -q "^tracking_fault_ticks: 0 ticks" "$work/out" || fail "rt_loop paper_pid counted faults"
echo "faults: counted, named and enforced"
