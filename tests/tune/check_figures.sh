#!/bin/sh
# The summary `fuzzypid tune` prints of its result on its training and validation runs (the worst
# |e| after 1 s, command reversals and torque saturation, each with its joint and condition) says
# what sim_ab measures running the written file on the same conditions; and a result still more
# than half of --divergence off the path on training is warned of, naming the remedies the
# condition lacks, with exit 0.
# Usage: check_figures.sh FUZZYPID SIM_AB CONDITIONS WORKDIR
set -eu
fuzzypid=$1
sim_ab=$2
conditions=$3
work=$4/figures
rm -rf "$work"
mkdir -p "$work"
cd "$work"
fail() {
  echo "check_figures.sh: $*" >&2
  exit 1
}
# The gains pinned (log10 per tick at 0.05 s): every evaluation is the same controller, too soft
# to hold the ER50 under gravity without a feed-forward.
tune() {
  "$fuzzypid" tune --family pid --conditions "$conditions" --budget 14 --population 7 \
    --box kp=1:1 --box ki=-1:-1 --box kd=2.3:2.3 --keep-filter --quiet "$@"
}

# The largest value of COLUMN over metrics.csv's rows, printed with FORMAT and UNIT, then
# " (joint J, CONDITION)" of the first row that has it, unless it is 0.
# Usage: worst FILE COLUMN FORMAT UNIT
worst() {
  awk -F, -v col="$2" -v fmt="$3" -v unit="$4" '
    NR == 1 { for (i = 1; i <= NF; ++i) if ($i == col) c = i; next }
    $(c) + 0 > best || NR == 2 { best = $(c) + 0; joint = $3; cond = $1 }
    END {
      out = sprintf(fmt, best) " " unit
      if (best > 0) out = out sprintf(" (joint %d, %s)", joint, cond)
      print out
    }' "$1"
}

tune --out pinned.toml >out.txt 2>err.txt || fail "tune exited $?: $(cat err.txt)"
"$sim_ab" --conditions "$conditions" --set training --controller pinned.toml --allow-faults \
  --out sim >/dev/null 2>&1 || fail "sim_ab exited $?"
error=$(worst sim/metrics.csv max_abs_error_after_1s_rad '%.3g' rad)
reversals=$(worst sim/metrics.csv reversals_pct '%.1f' "% of a joint's ticks")
saturated=$(worst sim/metrics.csv saturated_pct '%.1f' %)
want="result on its 3 training runs: |e| after 1 s up to $error; the command reverses on up to \
$reversals, the torque sits at a limit on up to $saturated"
grep -qxF "$want" out.txt || fail "expected '$want' in: $(cat out.txt)"

# Above half of the 1 rad default bound: warned, naming the worst run, the tick and the missing
# feed-forward (the ER50 has its armature: not named), exit 0.
value=${error%% *}
awk -v v="$value" 'BEGIN { exit !(v > 0.5 && v < 1.0) }' ||
  fail "the pinned result's |e| after 1 s is $value rad, not between 0.5 and 1: the test needs it"
grep -qF "warning: the result is still $value rad off the path after the first second of" err.txt ||
  fail "no warning: $(cat err.txt)"
grep -qF "a shorter tick (tick_ms; this one is 50 ms) or a --base with a gravity feed-forward" \
  err.txt || fail "remedies: $(cat err.txt)"
if grep -q armature err.txt; then fail "the ER50 has its armature: $(cat err.txt)"; fi

# Under half of a wider bound: no warning.
tune --divergence 2 --out wide.toml >wide.txt 2>wide_err.txt || fail "tune exited $?"
if grep -q warning wide_err.txt; then fail "warned at --divergence 2: $(cat wide_err.txt)"; fi

# With the last condition held back: one line for each part, each on its own runs.
tune --validation 1 --out validated.toml >validated.txt 2>&1 || fail "tune exited $?"
grep -q '^result on its 2 training runs: .*(joint [1-6], tool-behind)' validated.txt ||
  fail "training line: $(cat validated.txt)"
grep -q '^result on its 1 validation run: .*(joint [1-6], empty-ahead)' validated.txt ||
  fail "validation line: $(cat validated.txt)"
echo "check_figures.sh: |e| after 1 s $error; reversals $reversals; saturation $saturated"
