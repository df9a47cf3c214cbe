#!/bin/sh
# tune --per-joint-bandwidth: the result's file carries a bandwidth scale per joint (joint 1's is
# 1) and its box the five searched scales; sim_ab runs it with joint i's gains Kp s_i², Ki s_i³,
# Kd s_i (trajectory.csv's kp, ki, kd against joint 1's); export-header writes the joint-indexed
# functions; a start whose joint 1 is scaled is a usage error (exit 2, nothing written).
# Usage: check_tune_bandwidth.sh <fuzzypid> <sim_ab> <source dir> <work dir>
set -u
fuzzypid=$1
sim_ab=$2
src=$3
work=$4/tune_bandwidth
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
cond="$src/tests/tune/data/two_conditions.toml"
tune="$fuzzypid tune --family pid --conditions $cond --population 20 --seed 1 --threads 2 --quiet"
$tune --budget 200 --per-joint-bandwidth --out pj.toml 2>err || fail "tune: $(cat err)"
scales=$(sed -n 's/^bandwidth_scale = \[\(.*\)\]$/\1/p' pj.toml)
[ -n "$scales" ] || fail "pj.toml has no bandwidth_scale"
[ "$(echo "$scales" | tr ',' '\n' | wc -l)" -eq 6 ] || fail "not six scales: $scales"
[ "$(echo "$scales" | cut -d, -f1)" = "1.0" ] || fail "joint 1's scale is not 1: $scales"
for j in 2 3 4 5 6; do
  grep -q "name = \"bandwidth_j$j\", log10 = \[-1.0, 1.0\]" pj.toml || fail "no box of bandwidth_j$j"
done
# The scales differ from one another (the search moved them).
[ "$(echo "$scales" | tr ',' '\n' | sort -u | wc -l)" -gt 1 ] || fail "uniform scales: $scales"
"$sim_ab" --quiet --controller pj.toml --out run 2>err >/dev/null || fail "sim_ab: $(cat err)"
awk -F, -v s="$scales" '
  BEGIN { split(s, sc, ", ") }
  NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
  $(col["t"]) == 0 { kp[$(col["joint"])] = $(col["kp"]); ki[$(col["joint"])] = $(col["ki"]);
                     kd[$(col["joint"])] = $(col["kd"]) }
  END {
    for (j = 2; j <= 6; j++) {
      x = sc[j] + 0
      if (kp[1] <= 0 || (kp[j] / kp[1]) / (x * x) < 0.999999 || (kp[j] / kp[1]) / (x * x) > 1.000001)
        { print "joint " j " kp " kp[j] " vs " kp[1] " * " x "^2"; bad = 1 }
      if (kd[1] <= 0 || (kd[j] / kd[1]) / x < 0.999999 || (kd[j] / kd[1]) / x > 1.000001)
        { print "joint " j " kd " kd[j] " vs " kd[1] " * " x; bad = 1 }
      if (ki[1] > 0 && ((ki[j] / ki[1]) / (x * x * x) < 0.999999 || (ki[j] / ki[1]) / (x * x * x) > 1.000001))
        { print "joint " j " ki " ki[j] " vs " ki[1] " * " x "^3"; bad = 1 }
    }
    exit bad
  }' run/trajectory.csv >msg || fail "the gains sim_ab ran are not the scaled ones: $(cat msg)"
# settings.txt records the scales that ran.
grep -q "^controller\.pj=.* bandwidth_scale=1," run/settings.txt ||
  fail "settings.txt does not record the scales: $(grep '^controller' run/settings.txt)"
"$fuzzypid" export-header pj.toml --namespace pj --out pj.hpp --allow-uncertified 2>err ||
  fail "export-header: $(cat err)"
grep -q "make_controller(std::size_t joint, Scalar output_limit)" pj.hpp ||
  fail "the header's make_controller does not take the joint"
# A start whose joint 1 is scaled: refused before any work.
sed 's/^bandwidth_scale = \[1\.0,/bandwidth_scale = [2.0,/' pj.toml >start.toml
grep -q '^bandwidth_scale = \[2\.0,' start.toml || fail "could not write the scaled start"
$tune --budget 40 --per-joint-bandwidth --base start.toml --out never.toml 2>err
code=$?
[ "$code" -eq 2 ] || fail "a scaled joint 1 start: exit $code: $(cat err)"
grep -q "joint 1 has scale 1" err || fail "$(cat err)"
[ -e never.toml ] && fail "never.toml was written"
echo "tune bandwidth: ok ($scales)"
