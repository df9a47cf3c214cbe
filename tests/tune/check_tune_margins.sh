#!/bin/sh
# tune --min-disk-margin: the requirement binds (the free tune of the same seed keeps less margin
# than asked), the result keeps it on every joint and records it in [margins] with the
# certificate; a requirement no candidate meets exits 1 and writes nothing; sim_ab prints the
# record.
# Usage: check_tune_margins.sh <fuzzypid> <sim_ab> <source dir> <work dir>
set -u
fuzzypid=$1
sim_ab=$2
src=$3
work=$4/tune_margins
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
cond="$src/tests/tune/data/two_conditions.toml"
tune="$fuzzypid tune --family pid --conditions $cond --population 20 --seed 1 --threads 2 --quiet"
# The smallest disk margin over the joints of a controller file's [margins].
min_disk() {
  sed -n 's/^disk_margin = \[\(.*\)\]$/\1/p' "$1" | tr ',' '\n' | sort -g | head -n 1
}
$tune --budget 400 --out free.toml 2>err || fail "free tune: $(cat err)"
free=$(min_disk free.toml)
[ -n "$free" ] || fail "free.toml has no [margins] disk_margin"
awk -v d="$free" 'BEGIN { exit !(d < 1.2) }' || fail "the free tune already keeps $free >= 1.2"
$tune --budget 400 --min-disk-margin 1.2 --out kept.toml 2>err.kept ||
  fail "tune --min-disk-margin 1.2: $(cat err.kept)"
kept=$(min_disk kept.toml)
awk -v d="$kept" 'BEGIN { exit !(d >= 1.2) }' || fail "disk margin $kept < 1.2"
grep -qx 'min_disk_margin = 1.2' kept.toml || fail "the requirement is not recorded"
grep -qx 'certified = true' kept.toml || fail "not certified: $(grep verdict kept.toml)"
grep -q '^assumptions = "linear joint' kept.toml || fail "no assumptions recorded"
# The record covers the validation plants the search did not screen: a requirement met in the
# search but not over the record is warned of (the file written, exit 0).
late="$src/tests/tune/data/late_validation.toml"
$fuzzypid tune --family pid --conditions "$late" --validation 1 --population 20 --seed 1 \
  --threads 2 --budget 200 --min-disk-margin 1.2 --out late.toml 2>err || fail "late tune: $(cat err)"
late_disk=$(min_disk late.toml)
awk -v d="$late_disk" 'BEGIN { exit !(d < 1.2) }' || fail "the delayed validation plant kept $late_disk"
grep -q "warning: the result kept the required margins as the search screened them .* disk $(printf '%.3f' "$late_disk")" err ||
  fail "no warning that the record is short of the requirement: $(cat err)"
grep -q "warning: the result kept the required margins" err.kept 2>/dev/null &&
  fail "a record that keeps the requirement was warned of"
# Nothing reaches alpha = 1.99 (+-39 dB): exit 1, no file.
$tune --budget 100 --min-disk-margin 1.99 --out never.toml 2>err
code=$?
[ "$code" -eq 1 ] || fail "impossible requirement: exit $code"
grep -q "no candidate within the budget kept the required margins" err || fail "$(cat err)"
[ -e never.toml ] && fail "impossible requirement: never.toml was written"
# Bad values are usage errors.
$tune --budget 100 --min-disk-margin -1 --out bad.toml 2>err
[ $? -eq 2 ] || fail "--min-disk-margin -1 accepted"
# sim_ab prints the record.
"$sim_ab" --controller kept.toml --out run 2>err >/dev/null || fail "sim_ab: $(cat err)"
grep -q "sim_ab: margins of kept (recorded over .*two_conditions.toml \[training\]): disk 1\.[2-9]" err ||
  fail "sim_ab does not print the margins: $(cat err)"
echo "tune margins: ok (free $free, kept $kept)"
