#!/bin/sh
# A controller never silently does less than its file says: ticks on which the supervisor fires
# no rule are counted per joint (metrics.csv no_rule_ticks, rt_loop's no_rule_ticks line), warned
# about on stderr, and fail the run with --strict-rules (exit 1); retuned gains held at the file's
# bounds are counted (metrics.csv clamped_gain_ticks); settings.txt names the rule file that ran
# with its hash. Usage: check_rule_coverage.sh <sim_ab> <rt_loop> <source dir>
set -u
sim_ab=$1
rt_loop=$2
data=$3/tests/sim/data
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
# Column N of metrics.csv summed over the rows of controller C.
column_sum() { awk -F, -v c="$2" -v n="$3" 'NR > 1 && $2 == c { s += $n } END { print s + 0 }' "$1"; }

"$sim_ab" --quiet --controller "$data/gap_fuzzy.toml" --out "$work/gap" 2>"$work/err"
[ $? -eq 0 ] || fail "gap without --strict-rules: $(cat "$work/err")"
grep -q "warning: paper/gap_fuzzy: on [1-9][0-9]* joint-ticks the supervisor fired no rule" \
  "$work/err" || fail "no warning: $(cat "$work/err")"
head -1 "$work/gap/metrics.csv" | grep -q ",faults,no_rule_ticks,clamped_gain_ticks," ||
  fail "metrics.csv header"
[ "$(column_sum "$work/gap/metrics.csv" gap_fuzzy 12)" -gt 0 ] || fail "no_rule_ticks is 0"
grep -q "rule_file=$data/gap_supervisor.fll rule_file_fnv1a64=[0-9a-f]\{16\}" \
  "$work/gap/settings.txt" || fail "settings.txt: $(grep controller "$work/gap/settings.txt")"
grep -q "rule_base=" "$work/gap/settings.txt" && fail "settings.txt names a built-in rule base"

"$sim_ab" --quiet --strict-rules --controller "$data/gap_fuzzy.toml" --out "$work/strict" \
  2>"$work/err"
[ $? -eq 1 ] || fail "--strict-rules did not exit 1"
grep -q "in which a supervisor fired no rule (--strict-rules)" "$work/err" || fail "$(cat "$work/err")"
# As with controller faults, the output of the failed run is kept for diagnosis.
[ "$(column_sum "$work/strict/metrics.csv" gap_fuzzy 12)" -gt 0 ] || fail "strict: no count"

# The paper's tables cover the plane: no tick without a rule. (Their Ki does run into its lower
# bound 0, which is counted: Table 3 drives Ki below zero.)
"$sim_ab" --quiet --strict-rules --controller "$3/controllers/paper_fuzzy.toml" \
  --controller "$data/clamped_fuzzy.toml" --out "$work/paper" 2>"$work/err" ||
  fail "paper tables with --strict-rules: $(cat "$work/err")"
[ "$(column_sum "$work/paper/metrics.csv" paper_fuzzy 12)" -eq 0 ] || fail "paper: no_rule_ticks"
[ "$(column_sum "$work/paper/metrics.csv" clamped_fuzzy 13)" -gt 0 ] || fail "clamped: 0 ticks"

"$rt_loop" --period-ms 0 --controller "$data/gap_fuzzy.toml" >"$work/out" 2>"$work/err" ||
  fail "rt_loop gap: $(cat "$work/err")"
grep -q "^no_rule_ticks: [0-9,]* ticks (joints 1-6)$" "$work/out" || fail "rt_loop: $(cat "$work/out")"
grep -q "no_rule_ticks: 0,0,0,0,0,0" "$work/out" && fail "rt_loop counted nothing"
grep -q "warning: on [1-9][0-9]* joint-ticks the supervisor fired no rule" "$work/err" ||
  fail "rt_loop: no warning"
"$rt_loop" --period-ms 0 --strict-rules --controller "$data/gap_fuzzy.toml" >/dev/null 2>&1
[ $? -eq 1 ] || fail "rt_loop --strict-rules did not exit 1"
echo "rule coverage is counted, reported and enforced"
