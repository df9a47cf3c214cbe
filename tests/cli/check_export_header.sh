#!/bin/sh
# export-header generates code that compiles for every namespace it accepts, refuses the others
# with exit 2 and the reason, and refuses a controller whose values overflow float (exit 1).
# Usage: check_export_header.sh <fuzzypid> <c++ compiler> <source dir>
set -u
fuzzypid=$1
cxx=$2
src=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() {
  echo "FAIL: $*" >&2
  exit 1
}

# Accepted namespaces, each with another family, compiled as C++17 and GNU C++17 (which defines
# `linux` and `unix`) with the header's float and double controllers instantiated.
set -- fuzzypid_controller:paper_fuzzy my_robot::joint_6:tuned_pid Arm:tuned_scheduled \
  a::_b::c2:tuned_fuzzy ctrl_::x:paper_pid
for pair in "$@"; do
  ns=${pair%%:*}
  controller=${pair##*:}
  header="$work/$controller.hpp"
  "$fuzzypid" export-header "$src/controllers/$controller.toml" --namespace "$ns" --out "$header" \
    --allow-uncertified 2>"$work/err" || fail "--namespace $ns refused: $(cat "$work/err")"
  cat >"$work/use.cpp" <<EOF
#include "$header"
void use() {
  auto f = $ns::make_controller<float>(1.0f);
  auto d = $ns::make_controller<double>(1.0);
  (void)f;
  (void)d;
}
EOF
  for std in c++17 gnu++17; do
    "$cxx" -std=$std -fsyntax-only -Wall -Wextra -Wpedantic -Werror -I"$src/include" \
      "$work/use.cpp" 2>"$work/err" || fail "--namespace $ns ($std) does not compile: $(cat "$work/err")"
  done
done

# A controller whose supervisor is a rule file (its rule base becomes constexpr data) and a
# fuzzy-rules controller (its table becomes constexpr data) go through the command as well.
for file in tests/sim/data/engine_fuzzy.toml tests/cli/data/fuzzy_rules.toml; do
  header="$work/from_file.hpp"
  "$fuzzypid" export-header "$src/$file" --namespace from_file --out "$header" \
    --allow-uncertified 2>"$work/err" || fail "export-header $file refused: $(cat "$work/err")"
  cat >"$work/use.cpp" <<EOF
#include "$header"
void use() {
  auto f = from_file::make_controller<float>(1.0f);
  auto d = from_file::make_controller<double>(1.0);
  (void)f;
  (void)d;
}
EOF
  "$cxx" -std=c++17 -fsyntax-only -Wall -Wextra -Wpedantic -Werror -I"$src/include" \
    "$work/use.cpp" 2>"$work/err" || fail "$file's header does not compile: $(cat "$work/err")"
done

# Refused namespaces: exit 2, the reason on stderr, nothing written.
for ns in class int and xor_eq main std a::std fuzzypid a::fuzzypid final 1abc __x a__b _Abc _lower \
  a::_B NULL EOF errno linux unix 'a::' '::a' 'a:::b' 'a b' 'a-b' 'caf\303\251' '' 'a::b::'; do
  "$fuzzypid" export-header "$src/controllers/tuned_pid.toml" --namespace "$ns" \
    --out "$work/refused.hpp" >/dev/null 2>"$work/err"
  code=$?
  [ "$code" -eq 2 ] || fail "--namespace '$ns': exit $code, expected 2"
  grep -q "namespace" "$work/err" || fail "--namespace '$ns': no reason: $(cat "$work/err")"
  [ -e "$work/refused.hpp" ] && fail "--namespace '$ns': a header was written"
done

# The certificate: an uncertified controller (the paper's fuzzy PID: its Ki reaches 0) is refused
# with the reason (exit 1, nothing written) unless --allow-uncertified, which writes kCertified =
# false; a certified one (the tuned PID) carries kCertified = true and its margins, usable at
# compile time.
"$fuzzypid" export-header "$src/controllers/paper_fuzzy.toml" --out "$work/uncertified.hpp" \
  2>"$work/err"
code=$?
[ "$code" -eq 1 ] || fail "uncertified: exit $code, expected 1: $(cat "$work/err")"
grep -q "not certified (joint 1: Ki reaches 0" "$work/err" || fail "uncertified: $(cat "$work/err")"
[ -e "$work/uncertified.hpp" ] && fail "uncertified: a header was written"
"$fuzzypid" export-header "$src/controllers/paper_fuzzy.toml" --out "$work/uncertified.hpp" \
  --allow-uncertified 2>"$work/err" || fail "--allow-uncertified: $(cat "$work/err")"
grep -q "^inline constexpr bool kCertified = false;" "$work/uncertified.hpp" ||
  fail "--allow-uncertified: no kCertified = false"
"$fuzzypid" export-header "$src/controllers/tuned_pid.toml" --namespace certified \
  --out "$work/certified.hpp" 2>"$work/err" || fail "certified: $(cat "$work/err")"
grep -q "^// Assumptions: linear joint" "$work/certified.hpp" || fail "certified: no assumptions"
cat >"$work/use.cpp" <<EOF
#include "$work/certified.hpp"
static_assert(certified::kCertified, "the tuned PID is certified");
static_assert(certified::kDiskMargin[0] > 0.5 && certified::kGainMarginDb[5] > 3.0, "margins");
EOF
"$cxx" -std=c++17 -fsyntax-only -Wall -Wextra -Wpedantic -Werror -I"$src/include" \
  "$work/use.cpp" 2>"$work/err" || fail "certified header: $(cat "$work/err")"

# kp = 1e39 is a finite double but no float: refused (exit 1) with the value named.
sed 's/^kp = .*/kp = 1e39/' "$src/controllers/tuned_pid.toml" >"$work/huge.toml"
"$fuzzypid" export-header "$work/huge.toml" --out "$work/huge.hpp" 2>"$work/err"
code=$?
[ "$code" -eq 1 ] || fail "kp = 1e39: exit $code, expected 1: $(cat "$work/err")"
grep -q "kp is .* not finite as a float" "$work/err" || fail "kp = 1e39: $(cat "$work/err")"
[ -e "$work/huge.hpp" ] && fail "kp = 1e39: a header was written"
echo ok
