#!/bin/sh
# certify --record: the certificate replaces the controller file's [margins] record (every figure
# equal to --json's, the conditions named from the file's folder, the set), the rest of the file is
# unchanged, a second record is byte-identical; --record without --conditions or with --grid exits
# 2 and an unwritable folder exits 1, each leaving the file as it was. Every shipped tuned file's
# record is the one certify computes today over the conditions and set it names.
# Usage: check_certify_record.sh <fuzzypid> <source dir> <python3>
set -u
fuzzypid=$1
src=$2
python=$3
work=$(mktemp -d)
trap 'chmod -R u+w "$work"; rm -rf "$work"' EXIT
fail() {
  echo "FAIL: $*" >&2
  exit 1
}

# A per-joint schedule (moving gains, not certified over the drive plants) and the shipped PID.
mkdir -p "$work/c"
cp "$src/tests/sim/data/per_joint_scheduled.toml" "$work/c/schedule.toml"
cp "$src/controllers/tuned_pid.toml" "$work/c/pid.toml"
conditions="$src/tuning/robust_drive.toml"
for case in schedule:held-out pid:training; do
  name=${case%%:*}
  set=${case#*:}
  f="$work/c/$name.toml"
  cp "$f" "$work/$name.before"
  "$fuzzypid" certify "$f" --conditions "$conditions" --set "$set" --json >"$work/$name.json"
  want=$?
  "$fuzzypid" certify "$f" --conditions "$conditions" --set "$set" --record --json \
    >"$work/$name.recorded.json"
  got=$?
  [ "$got" -eq "$want" ] || fail "$name: --record exits $got, certify $want"
  cmp -s "$work/$name.json" "$work/$name.recorded.json" || fail "$name: --record changes the output"
  "$python" - "$work/$name.before" "$f" "$work/$name.json" "$conditions" "$set" <<'PY' ||
import json, math, os, sys, tomllib
val = lambda v: math.inf if v is None else v  # JSON writes an infinite margin as null
before = tomllib.load(open(sys.argv[1], "rb"))
after = tomllib.load(open(sys.argv[2], "rb"))
cert = json.load(open(sys.argv[3]))
m = after["margins"]
# The record names the conditions from the file's folder and the set it covers.
named = os.path.normpath(os.path.join(os.path.dirname(sys.argv[2]), m["conditions"]))
assert os.path.samefile(named, sys.argv[4]), (m["conditions"], named)
assert m["set"] == sys.argv[5], m
assert m["certified"] == cert["certified"], (m["certified"], cert["certified"])
assert m["verdict"] == cert["verdict"], (m["verdict"], cert["verdict"])
for key in ("gain_margin_db", "phase_margin_deg", "delay_margin_ms", "disk_margin"):
    assert m[key] == [val(j[key]) for j in cert["joints"]], (key, m[key])
assert m["delay_ms"] == cert["delay_ms"], (m["delay_ms"], cert["delay_ms"])
# Nothing but the record changed.
before.pop("margins", None)
after.pop("margins")
assert before == after, "a section other than [margins] changed"
PY
    fail "$name: the record is not the certificate"
  cp "$f" "$work/$name.once"
  "$fuzzypid" certify "$f" --conditions "$conditions" --set "$set" --record >/dev/null
  cmp -s "$f" "$work/$name.once" || fail "$name: a second --record changes the file"
done

# Refusals leave the file as it was.
f="$work/c/schedule.toml"
cp "$f" "$work/kept"
"$fuzzypid" certify "$f" --record >"$work/out" 2>&1
[ $? -eq 2 ] || fail "--record without --conditions does not exit 2"
grep -q -- "--record: needs --conditions" "$work/out" || fail "no message: $(cat "$work/out")"
"$fuzzypid" certify "$f" --conditions "$conditions" --set training --record --grid 5 \
  >"$work/out" 2>&1
[ $? -eq 2 ] || fail "--record with --grid does not exit 2"
grep -q -- "--record: .*--grid" "$work/out" || fail "no message: $(cat "$work/out")"
chmod a-w "$work/c"
"$fuzzypid" certify "$f" --conditions "$conditions" --set held-out --record >"$work/out" 2>&1
[ $? -eq 1 ] || fail "an unwritable folder does not exit 1"
grep -q -- "--record: .*schedule.toml" "$work/out" || fail "no message: $(cat "$work/out")"
chmod u+w "$work/c"
cmp -s "$f" "$work/kept" || fail "a refused --record changed the file"

# The shipped files' records are current: what certify computes today over the conditions and set
# each record names (a record left from an older model would differ).
for f in "$src"/controllers/*.toml; do
  grep -q '^\[margins\]' "$f" || continue
  "$python" - "$f" >"$work/args" <<'PY' || fail "$f: no conditions in its record"
import os, sys, tomllib
m = tomllib.load(open(sys.argv[1], "rb"))["margins"]
print(os.path.join(os.path.dirname(sys.argv[1]), m["conditions"]))
print(m["set"])
PY
  c=$(sed -n 1p "$work/args")
  s=$(sed -n 2p "$work/args")
  "$fuzzypid" certify "$f" --conditions "$c" --set "$s" --json >"$work/now.json" 2>/dev/null
  "$python" - "$f" "$work/now.json" <<'PY' || fail "$f: its [margins] record is not today's certificate (re-record it with certify --record)"
import json, math, sys, tomllib
val = lambda v: math.inf if v is None else v  # JSON writes an infinite margin as null
m = tomllib.load(open(sys.argv[1], "rb"))["margins"]
cert = json.load(open(sys.argv[2]))
assert m["certified"] == cert["certified"] and m["verdict"] == cert["verdict"], m["verdict"]
for key in ("gain_margin_db", "phase_margin_deg", "delay_margin_ms", "disk_margin"):
    for r, j in zip(m[key], cert["joints"]):
        assert math.isclose(r, val(j[key]), rel_tol=1e-9, abs_tol=1e-12), (key, r, j[key])
PY
done
echo "certify --record: ok"
