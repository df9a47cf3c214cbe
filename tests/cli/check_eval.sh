#!/bin/sh
# ctest cases for `fuzzypid eval`. Usage: check_eval.sh <path to fuzzypid> <case>
# Expected outputs are derived by hand from Tables 2-4 and Eq. 8, not recorded from the tool.
set -u
tool=$1
case_name=$2
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
  *)
    fail "unknown case"
    ;;
esac
echo "ok ($case_name)"
