#!/bin/sh
# ctest cases for `fuzzypid eval`. Usage: check_eval.sh <path to fuzzypid> <case>
# Expected outputs are derived by hand from Tables 2-4 and Eq. 8, not recorded from the tool.
set -u
tool=$1
case_name=$2
data=${3:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

fail() {
  echo "FAIL ($case_name): $*" >&2
  exit 1
}

# run <stdin text> <args...>: runs the tool, leaves stdout/stderr in $work and the code in $code.
run() {
  input=$1
  shift
  printf '%s' "$input" | "$tool" eval "$@" >"$work/out" 2>"$work/err"
  code=$?
}

# expect_rows <file of expected e,ec,dKp,dKi,dKd rows>: every output row matches to 1e-15.
expect_rows() {
  head -n 1 "$work/out" | grep -qx 'e,ec,dKp,dKi,dKd' || fail "missing header line: $(head -n 1 "$work/out")"
  tail -n +2 "$work/out" >"$work/rows"
  [ "$(wc -l <"$work/rows")" -eq "$(wc -l <"$1")" ] || fail "row count differs: $(cat "$work/out")"
  paste -d, "$work/rows" "$1" | awk -F, '
    function abs(x) { return x < 0 ? -x : x }
    { for (k = 1; k <= 5; ++k) if (abs($k - $(k + 5)) > 1e-15) {
        printf "line %d column %d: got %s, expected %s\n", NR, k, $k, $(k + 5); bad = 1 } }
    END { exit bad }' || fail "outputs differ"
}

# Rows: on the (ZE, ZE), (NL, NL), (PL, NM) peaks, far outside the universe (saturates to
# (PL, NL)), and between peaks (e = 0.05: ZE 0.5, PS 0.5; ec = -0.12: NM 0.2, NS 0.8).
input='e,ec
0,0
-0.3,-0.3
0.3,-0.2
5,-5
0.05,-0.12
'

case $case_name in
  known_rows)
    run "$input"
    [ "$code" -eq 0 ] || fail "exit code $code: $(cat "$work/err")"
    cat >"$work/expected" <<'ROWS'
0,0,0,0,-0.1
-0.3,-0.3,0.03,-0.03,0.1
0.3,-0.2,0,0,0.2
5,-5,0,0,0.3
0.05,-0.12,0.0078571428571428571,-0.0078571428571428571,-0.05
ROWS
    expect_rows "$work/expected"
    ;;
  and_prod_differs)
    run "$input" --and prod
    [ "$code" -eq 0 ] || fail "exit code $code: $(cat "$work/err")"
    # Product strengths 0.1, 0.4, 0.1, 0.4 (sum 1) instead of min's 0.2, 0.5, 0.2, 0.5.
    cat >"$work/expected" <<'ROWS'
0,0,0,0,-0.1
-0.3,-0.3,0.03,-0.03,0.1
0.3,-0.2,0,0,0.2
5,-5,0,0,0.3
0.05,-0.12,0.007,-0.007,-0.05
ROWS
    expect_rows "$work/expected"
    cp "$work/out" "$work/prod"
    run "$input" --and min
    cmp -s "$work/out" "$work/prod" && fail "--and prod gives the same output as --and min"
    ;;
  full_precision)
    run '0.05,-0.12
'
    [ "$code" -eq 0 ] || fail "exit code $code"
    # %.17g round-trips a double: 0.011 / 1.4 printed with 17 significant digits.
    grep -q '^0.050000000000000003,-0.12,0.00785714285714285[0-9]*,' "$work/out" ||
      fail "not printed with %.17g: $(cat "$work/out")"
    ;;
  bad_row_names_the_line)
    run 'e,ec
0.1,0.2
0.1,abc
0.2,0.2
'
    [ "$code" -eq 1 ] || fail "exit code $code, expected 1"
    grep -q 'line 3' "$work/err" || fail "stderr does not name line 3: $(cat "$work/err")"
    ;;
  wrong_column_count_names_the_line)
    run '0.1,0.2
0.1,0.2,0.3
'
    [ "$code" -eq 1 ] || fail "exit code $code, expected 1"
    grep -q 'line 2' "$work/err" || fail "stderr does not name line 2: $(cat "$work/err")"
    ;;
  bad_option_exits_2)
    run '0,0
' --and max
    [ "$code" -eq 2 ] || fail "--and max: exit code $code, expected 2"
    [ -s "$work/err" ] || fail "--and max: no message on stderr"
    run '0,0
' --bogus
    [ "$code" -eq 2 ] || fail "--bogus: exit code $code, expected 2"
    run '0,0
' --and
    [ "$code" -eq 2 ] || fail "--and without a value: exit code $code, expected 2"
    ;;
  header_must_be_text)
    # A first row of NaN, inf or overflowing numbers is data (and an error), never a header.
    for first in 'nan,nan' 'inf,-inf' '1e999,-1e999' 'nan,e'; do
      run "$first
0.1,0.2
"
      [ "$code" -eq 1 ] || fail "first row '$first': exit code $code, expected 1"
      grep -q 'line 1: column 1' "$work/err" || fail "first row '$first': $(cat "$work/err")"
    done
    # A text header is skipped and the next row evaluated.
    run 'error , rate
0,0
'
    [ "$code" -eq 0 ] || fail "text header: exit code $code: $(cat "$work/err")"
    [ "$(wc -l <"$work/out")" -eq 2 ] || fail "text header: $(cat "$work/out")"
    ;;
  huge_line_is_an_error)
    # 200 MB of digits on one line: refused at the line bound, neither a header nor a number.
    (yes 1111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111 |
      tr -d '\n' | head -c 200000000) | "$tool" eval >"$work/out" 2>"$work/err"
    code=$?
    [ "$code" -eq 1 ] || fail "exit code $code, expected 1"
    grep -q 'line 1: longer than' "$work/err" || fail "stderr: $(cat "$work/err")"
    ;;
  full_stdout_fails)
    printf '0,0\n' | "$tool" eval >/dev/full 2>"$work/err"
    code=$?
    [ "$code" -eq 1 ] || fail "> /dev/full: exit code $code, expected 1"
    grep -q 'cannot write standard output' "$work/err" || fail "stderr: $(cat "$work/err")"
    ;;
  unreadable_stdin_fails)
    "$tool" eval <"$work" >"$work/out" 2>"$work/err"
    code=$?
    [ "$code" -eq 1 ] || fail "stdin a directory: exit code $code, expected 1"
    grep -q 'standard input is a directory' "$work/err" || fail "stderr: $(cat "$work/err")"
    : >"$work/w"
    "$tool" eval 0>"$work/w" >"$work/out" 2>"$work/err"
    code=$?
    [ "$code" -eq 1 ] || fail "stdin write-only: exit code $code, expected 1"
    grep -q 'cannot read standard input' "$work/err" || fail "stderr: $(cat "$work/err")"
    ;;
  no_rule_fired_is_reported)
    # gap.fll has no term covering 0.4 < x < 0.6: the row is written (default 0) and named.
    run 'x
0.2
0.5
0.8
' --fll "$data/gap.fll"
    [ "$code" -eq 1 ] || fail "exit code $code, expected 1"
    grep -q 'line 3: no rule fired' "$work/err" || fail "stderr: $(cat "$work/err")"
    [ "$(sed -n 3p "$work/out")" = "0.5,0" ] || fail "row 2: $(cat "$work/out")"
    run '0.2
0.8
' --fll "$data/gap.fll"
    [ "$code" -eq 0 ] || fail "rows that fire: exit code $code: $(cat "$work/err")"
    ;;
  fcl_option_reads_fcl)
    # --fcl reads IEC 61131-7 text whatever the file is called, and only that.
    cp tests/rulefile/data/corpus/fcl_motor_speed_pi.fcl "$work/motor.txt"
    run 'e,de
0.1,-0.2
' --fcl "$work/motor.txt"
    [ "$code" -eq 0 ] || fail "--fcl: exit code $code: $(cat "$work/err")"
    [ "$(head -n 1 "$work/out")" = "e,de,du" ] || fail "--fcl header: $(cat "$work/out")"
    [ "$(wc -l <"$work/out")" -eq 2 ] || fail "--fcl rows: $(cat "$work/out")"
    run '0,0
' --fcl rulebases/paper.fis
    [ "$code" -eq 1 ] || fail "--fcl on a .fis file: exit code $code, expected 1"
    ;;
  rule_file_options_exclude_each_other)
    run '0,0
' --fis rulebases/paper.fis --fll rulebases/paper.fll
    [ "$code" -eq 2 ] || fail "--fis with --fll: exit code $code, expected 2"
    run '0,0
' --fll "$data/gap.fll" --and prod
    [ "$code" -eq 2 ] || fail "--fll with --and: exit code $code, expected 2"
    ;;
  rule_file_read_is_bounded)
    run '0,0
' --fis /dev/zero
    [ "$code" -eq 1 ] || fail "--fis /dev/zero: exit code $code, expected 1"
    grep -q "'/dev/zero' is a character device, not a regular file" "$work/err" ||
      fail "no kind message: $(cat "$work/err")"
    ;;
  *)
    fail "unknown case"
    ;;
esac
echo "ok ($case_name)"
