#!/bin/sh
# export-rules: the fuzzy controller written by --controller-out, running the exported .fll, .fcl
# (and, for ratios R = 1, .fis) rule file, follows the fuzzy-rules controller it came from on every
# sim_ab scenario to 1e-9 rad (and its gains to 1e-9 relative); other families, .fis with R != 1
# and bad usage are refused with the reason and nothing written.
# Usage: check_export_rules.sh <fuzzypid> <sim_ab> <source dir>
set -u
fuzzypid=$1
sim_ab=$2
src=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
rules_controller="$src/tests/cli/data/fuzzy_rules.toml"

# same_runs A B: trajectory.csv of the two runs row by row (the controller's name aside): the same
# conditions, ticks and joints, |theta_A - theta_B| <= 1e-9 rad, gains within 1e-9 relative.
same_runs() {
  paste -d, "$1/trajectory.csv" "$2/trajectory.csv" | awk -F, '
    NR == 1 { n = NF / 2; next }
    $1 != $(n + 1) || $3 != $(n + 3) || $4 != $(n + 4) { print "row " NR ": not the same condition, tick or joint"; bad = 1; exit }
    {
      d = $6 - $(n + 6); if (d < 0) d = -d; if (d > theta) theta = d
      for (k = 10; k <= 12; ++k) {
        g = $k - $(k + n); if (g < 0) g = -g
        s = $k < 0 ? -$k : $k; if (s > 1) g /= s
        if (g > gain) gain = g
      }
      rows++
    }
    END {
      if (bad) exit 1
      printf "%d rows: max |theta difference| %.3g rad, max gain difference %.3g (relative)\n", rows, theta, gain
      if (rows < 1000 || theta > 1e-9 || gain > 1e-9) exit 1
    }' || fail "$3: the runs differ"
  [ "$(wc -l <"$1/trajectory.csv")" -eq "$(wc -l <"$2/trajectory.csv")" ] ||
    fail "$3: different row counts"
}

# The hand-made controller diverges on the saturation scenario: what is compared here is the
# trajectory, so its faults are accepted (--allow-faults; with R = 1 below it diverges on the
# paper scenario too).
"$sim_ab" --quiet --allow-faults --scenario all --controller "$rules_controller" --out "$work/reference" \
  2>"$work/err" || fail "sim_ab on the fuzzy-rules controller: $(cat "$work/err")"

# The rule file in one folder, the controller in another: the controller names it relatively.
mkdir "$work/rules" "$work/controllers"
for format in fll fcl; do
  "$fuzzypid" export-rules "$rules_controller" --format $format --out "$work/rules/exported.$format" \
    --controller-out "$work/controllers/exported_$format.toml" 2>"$work/err" ||
    fail "export-rules --format $format: $(cat "$work/err")"
  grep -q "^family = \"fuzzy\"" "$work/controllers/exported_$format.toml" || fail "$format: not fuzzy"
  grep -q "^rule_file = \"../rules/exported.$format\"" "$work/controllers/exported_$format.toml" ||
    fail "$format: rule_file: $(grep rule_file "$work/controllers/exported_$format.toml")"
  grep -q "^description = .*fuzzy_rules.toml" "$work/controllers/exported_$format.toml" ||
    fail "$format: the description does not say where the controller came from"
  "$sim_ab" --quiet --allow-faults --scenario all --controller "$work/controllers/exported_$format.toml" \
    --out "$work/run_$format" 2>"$work/err" || fail "sim_ab on the exported $format: $(cat "$work/err")"
  printf '%s: ' "$format"
  same_runs "$work/reference" "$work/run_$format" "$format"
done

# .fis holds the table alone: with R = 1 it round-trips too (the format taken from --out).
sed 's/^output_scale = .*/output_scale = [1.0, 1.0, 1.0]/' "$rules_controller" >"$work/unit_r.toml"
"$fuzzypid" export-rules "$work/unit_r.toml" --out "$work/unit_r.fis" \
  --controller-out "$work/unit_r_fuzzy.toml" 2>"$work/err" || fail "export-rules .fis: $(cat "$work/err")"
grep -q "^\[System\]" "$work/unit_r.fis" || fail ".fis: not a .fis file"
"$sim_ab" --quiet --allow-faults --scenario all --controller "$work/unit_r.toml" --out "$work/unit_r_reference" \
  2>"$work/err" || fail "sim_ab, R = 1: $(cat "$work/err")"
"$sim_ab" --quiet --allow-faults --scenario all --controller "$work/unit_r_fuzzy.toml" --out "$work/run_fis" \
  2>"$work/err" || fail "sim_ab on the exported fis: $(cat "$work/err")"
printf 'fis: '
same_runs "$work/unit_r_reference" "$work/run_fis" fis

# refused CODE PATTERN ARGS...: the exit code, the reason on stderr, nothing written to $work/out*.
refused() {
  code=$1
  pattern=$2
  shift 2
  "$fuzzypid" export-rules "$@" >"$work/stdout" 2>"$work/err"
  got=$?
  [ "$got" -eq "$code" ] || fail "export-rules $*: exit $got, expected $code: $(cat "$work/err")"
  grep -Eq -- "$pattern" "$work/err" || fail "export-rules $*: no '$pattern' in: $(cat "$work/err")"
  ls "$work" | grep -q '^out' && fail "export-rules $*: wrote $(ls "$work" | grep '^out')"
  true
}
for other in paper_pid tuned_scheduled tuned_fuzzy; do
  refused 1 "a '[a-z]+' controller has no rule table" "$src/controllers/$other.toml" --out "$work/out.fll"
done
refused 1 "\\.fis file cannot express the schedule's ramp" "$rules_controller" --out "$work/out.fis" \
  --controller-out "$work/out.toml"
refused 2 "nothing to write" "$rules_controller"
refused 2 "--controller-out: needs --out" "$rules_controller" --controller-out "$work/out.toml"
refused 2 "--format: not given" "$rules_controller" --out "$work/out.txt"
refused 2 "--out: .* ends in \\.fcl but --format is fll" "$rules_controller" --format fll --out "$work/out.fcl"
refused 2 "--out: .* must end in \\.fll" "$rules_controller" --format fll --out "$work/out.txt" \
  --controller-out "$work/out.toml"
refused 2 "--format" "$rules_controller" --format xml --out "$work/out.xml"
refused 2 "--surface-points" "$rules_controller" --surface "$work/out.csv" --surface-points 2
refused 2 "--out: .*same file as the input" "$rules_controller" --format fll --out "$rules_controller"
refused 2 "--controller-out: .*same file as the input" "$rules_controller" --out "$work/out.fll" \
  --controller-out "$rules_controller"
refused 2 "--controller-out: .*same file as --out" "$rules_controller" --out "$work/out.fll" \
  --controller-out "$work/../$(basename "$work")/out.fll"
refused 2 "--surface: .*is a folder" "$rules_controller" --surface "$work/rules"
refused 1 "No such file|cannot open" "$work/missing.toml" --out "$work/out.fll"

# The surface: a square grid with the ratios at the nodes the table gives (x = 0, y = 0 is the
# center cell: kp 0.94, ki 1.0, kd 1.2 with the ramp at 0).
"$fuzzypid" export-rules "$rules_controller" --surface "$work/surface.csv" --surface-points 5 \
  2>"$work/err" || fail "--surface: $(cat "$work/err")"
[ "$(head -1 "$work/surface.csv")" = "e_rad,ec_rad_s,kp_ratio,ki_ratio,kd_ratio" ] ||
  fail "--surface header: $(head -1 "$work/surface.csv")"
[ "$(wc -l <"$work/surface.csv")" -eq 26 ] || fail "--surface: $(wc -l <"$work/surface.csv") lines"
grep -q "^0,0,0.93999999999999995,1,1.2$" "$work/surface.csv" ||
  fail "--surface: no center row: $(sed -n 14p "$work/surface.csv")"
echo ok
