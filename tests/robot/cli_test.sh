#!/bin/sh
# End-to-end test of `fuzzypid fk` and `fuzzypid ik`. Usage: cli_test.sh FUZZYPID_BINARY DATA_DIR
set -u
bin=$1
data=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0

fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}

# expect_exit CODE STDERR_FRAGMENT COMMAND... (stdin from $tmp/in)
expect_exit() {
  code=$1
  fragment=$2
  shift 2
  "$@" <"$tmp/in" >"$tmp/out" 2>"$tmp/err"
  got=$?
  [ "$got" -eq "$code" ] || fail "'$*' exited $got, expected $code (stderr: $(cat "$tmp/err"))"
  if [ -n "$fragment" ] && ! grep -q -- "$fragment" "$tmp/err"; then
    fail "'$*' stderr lacks '$fragment': $(cat "$tmp/err")"
  fi
}

# 1. fk at q = 0: the wrist center is (1.280, 0, -0.451) m with tip axes x0, -y0, -z0.
printf 'q1,q2,q3,q4,q5,q6\n0,0,0,0,0,0\n' >"$tmp/in"
expect_exit 0 "" "$bin" fk
awk -F, 'function abs(v) { return v < 0 ? -v : v }
  { e[1]=1.28; e[2]=0; e[3]=-0.451; e[4]=1; e[5]=0; e[6]=0; e[7]=0; e[8]=-1; e[9]=0; e[10]=0;
    e[11]=0; e[12]=-1; if (NF != 12) exit 1; for (i = 1; i <= 12; ++i) if (abs($i - e[i]) > 1e-12) exit 1 }
  END { if (NR != 1) exit 1 }' "$tmp/out" || fail "fk at q = 0 printed: $(cat "$tmp/out")"

# 2. fk | ik round trip for every solver, with the original q appended as the seed.
cat >"$tmp/q" <<'ROWS'
0.176,-0.701,0.079,-0.0002,-0.949,-1.019
-0.236,-0.166,-0.691,0,-0.715,-0.237
0.5,-1.0,0.8,1.2,0.6,-2.0
-2.0,0.3,1.5,-3.0,-1.8,5.0
ROWS
cp "$tmp/q" "$tmp/in"
expect_exit 0 "" "$bin" fk
paste -d, "$tmp/out" "$tmp/q" >"$tmp/in"
for solver in analytic kdl-nr kdl-lma; do
  expect_exit 0 "" "$bin" ik --solver "$solver"
  paste -d, "$tmp/out" "$tmp/q" | awk -F, -v s="$solver" '
    function abs(v) { return v < 0 ? -v : v }
    { if (NF != 13 || $7 != "ok") { print s ": row " NR ": " $0; bad = 1; next }
      for (i = 1; i <= 6; ++i) if (abs($i - $(7 + i)) > 1e-6) { print s ": row " NR ": " $0; bad = 1 } }
    END { if (NR != 4) bad = 1; exit bad }' >&2 || fail "ik --solver $solver round trip"
done

# 3. Without a seed the closed form still answers (nearest q = 0).
cut -d, -f1-12 "$tmp/in" >"$tmp/in2" && mv "$tmp/in2" "$tmp/in"
expect_exit 0 "" "$bin" ik
[ "$(grep -c ',ok$' "$tmp/out")" -eq 4 ] || fail "ik without seeds: $(cat "$tmp/out")"

# 4. An unreachable pose is a status, not an error; the seed (zeros) is echoed.
printf '5,0,0,1,0,0,0,1,0,0,0,1\n' >"$tmp/in"
expect_exit 0 "" "$bin" ik
grep -q '^0,0,0,0,0,0,unreachable$' "$tmp/out" || fail "unreachable row printed: $(cat "$tmp/out")"
expect_exit 0 "" "$bin" ik --solver kdl-nr
grep -q ',no_convergence$' "$tmp/out" || fail "kdl-nr unreachable printed: $(cat "$tmp/out")"

# 5. Malformed rows exit 1 and name the line.
printf '0,0,0,0,0,0\n0,0,abc,0,0,0\n' >"$tmp/in"
expect_exit 1 "line 2" "$bin" fk
printf '0,0,0,0,0,0\nnan,0,0,0,0,0\n' >"$tmp/in"
expect_exit 1 "line 2" "$bin" fk
printf '0,0,0,0,0\n' >"$tmp/in"
expect_exit 1 "line 1" "$bin" fk
printf '1.28,0,-0.451,1,0,0,0,-1,0,0,0,-1,0,0\n' >"$tmp/in"
expect_exit 1 "line 1" "$bin" ik
printf '# comment\n1.28,0,-0.451,2,0,0,0,-1,0,0,0,-1\n' >"$tmp/in"
expect_exit 1 "line 2" "$bin" ik
printf '1.28,0,-0.451,1,0,0,0,-1,0,0,0,-1,inf,0,0,0,0,0\n' >"$tmp/in"
expect_exit 1 "line 1" "$bin" ik

# 6. URDFs that do not load exit 1 with the reason; bad usage exits 2.
printf '0,0,0,0,0,0\n' >"$tmp/in"
expect_exit 1 "cannot open" "$bin" fk --urdf "$tmp/missing.urdf"
expect_exit 1 "not a valid URDF" "$bin" fk --urdf "$data/malformed.urdf"
expect_exit 1 "has 5 movable joints" "$bin" ik --urdf "$data/five_joints.urdf"
expect_exit 2 "is not analytic, kdl-nr or kdl-lma" "$bin" ik --solver newton
expect_exit 2 "was not expected" "$bin" fk --frobnicate
expect_exit 2 "" "$bin" fk --urdf

# 7. Unbounded or physically meaningless URDFs are refused with the element named (before, a
# zero-length axis loaded and fk printed -nan with exit 0).
expect_exit 1 "is a character device, not a regular file" "$bin" fk --urdf /dev/zero
expect_exit 1 "is a directory" "$bin" fk --urdf "$tmp"
sed '0,/<axis xyz="0 0 1"\/>/s//<axis xyz="0 0 0"\/>/' "$data/../../../urdf/er50_c20.urdf" >"$tmp/zero_axis.urdf"
expect_exit 1 "joint 'joint1': <axis> must be a finite non-zero vector" "$bin" fk --urdf "$tmp/zero_axis.urdf"
[ -s "$tmp/out" ] && fail "fk with a zero axis printed: $(cat "$tmp/out")"

# 8. Output that cannot be written and input that cannot be read are errors.
expect_exit 0 "" "$bin" fk
"$bin" fk <"$tmp/in" >/dev/full 2>"$tmp/err"
[ $? -eq 1 ] || fail "fk > /dev/full did not exit 1"
grep -q "cannot write standard output" "$tmp/err" || fail "fk > /dev/full: $(cat "$tmp/err")"
"$bin" ik <"$tmp" >"$tmp/out" 2>"$tmp/err"
[ $? -eq 1 ] || fail "ik < directory did not exit 1"
grep -q "standard input is a directory" "$tmp/err" || fail "ik < directory: $(cat "$tmp/err")"

if [ "$failures" -ne 0 ]; then
  echo "$failures check(s) failed" >&2
  exit 1
fi
echo "cli_test: all checks passed"
