#!/bin/sh
# Every tool's outputs follow one contract (apps/common/output_files.hpp, docs/robustness.md
# "Outputs"): a path that cannot be written -- '' , a missing or read-only folder, a folder, a
# device, a FIFO, or one of the run's own inputs under any spelling -- is a usage error (exit 2)
# reported before any work, and the node or input is left exactly as it was; a write that fails
# (the file-size limit; as root also a full tmpfs) exits 1 and keeps the previous file.
# Device nodes and FIFOs are private ones made in a temporary folder, never the system's.
# Usage: check_outputs.sh <fuzzypid> <rt_loop> <sim_ab> <source dir>
set -u
fuzzypid=$1
rt_loop=$2
sim_ab=$3
src=$4
work=$(mktemp -d)
trap 'chmod -R u+w "$work"; rm -rf "$work"' EXIT
cd "$work" || exit 1
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
# refused PATTERN CMD...: exit 2, PATTERN on stderr, nothing on stdout, within 20 s (a tune with
# a budget of 10^8 evaluations proves that the refusal comes before the work).
refused() {
  pattern=$1
  shift
  timeout 20 "$@" >out 2>err
  code=$?
  [ "$code" -eq 2 ] || fail "$*: exit $code, expected 2: $(cat err)"
  grep -Eq -- "$pattern" err || fail "$*: no '$pattern' in: $(cat err)"
  [ -s out ] && fail "$*: wrote on stdout: $(cat out)"
  true
}

cp "$src/controllers/tuned_pid.toml" c.toml
cp "$src/tuning/robust.toml" cond.toml
cp c.toml c.orig
cp cond.toml cond.orig
ln -s c.toml link.toml
ln -s cond.toml cond_link.toml
mkdir folder ro
chmod 555 ro
mkfifo fifo
have_dev=0
if mknod full c 1 7 2>/dev/null; then have_dev=1; else echo "note: mknod refused: device case skipped"; fi

tune="$fuzzypid tune --family pid --budget 100000000 --population 20 --threads 1 --quiet"
for out in missing/x.toml folder ro/x.toml '' fifo; do
  refused "--out" $tune --conditions cond.toml --out "$out"
done
refused "same file as the input" $tune --conditions cond.toml --out cond.toml
refused "same file as the input" $tune --conditions cond_link.toml --out ./cond.toml
refused "same file as the input" $tune --conditions cond.toml --base c.toml --out link.toml
refused "is a folder" $fuzzypid export-header c.toml --out folder
refused "--out: empty value" $fuzzypid export-header c.toml --out ''
refused "No such file or directory" $fuzzypid export-header c.toml --out missing/x.hpp
refused "read-only|Permission denied" $fuzzypid export-header c.toml --out ro/x.hpp
refused "same file as the input" $fuzzypid export-header c.toml --out c.toml
refused "same file as the input" $fuzzypid export-header c.toml --out link.toml
refused "same file as the input" $fuzzypid export-header link.toml --out "$work/c.toml"
refused "FIFO" $fuzzypid export-header c.toml --out fifo
refused "is a folder" $fuzzypid export-rules c.toml --format fll --out folder
refused "same file as the input" $fuzzypid export-rules c.toml --format fll --out link.toml
refused "same file as the input" $fuzzypid export-rules c.toml --out x.fll --controller-out c.toml
refused "read-only|Permission denied" $fuzzypid export-rules c.toml --out x.fll --controller-out ro/x.toml
refused "FIFO" $fuzzypid export-rules c.toml --surface fifo
refused "--csv: empty value" "$rt_loop" --period-ms 0 --ticks 3 --csv ''
refused "same file as the input" "$rt_loop" --period-ms 0 --ticks 3 --controller c.toml --csv c.toml
refused "same file as the input" "$rt_loop" --period-ms 0 --ticks 3 --controller link.toml --csv c.toml
refused "FIFO" "$rt_loop" --period-ms 0 --ticks 3 --csv fifo
refused "is a folder" "$rt_loop" --period-ms 0 --ticks 3 --csv folder
refused "not an output folder" "$sim_ab" --quiet --out c.toml
refused "FIFO" "$sim_ab" --quiet --out fifo
refused "read-only|Permission denied" "$sim_ab" --quiet --out ro/out
if [ "$have_dev" -eq 1 ]; then
  refused "character device" $tune --conditions cond.toml --out full
  refused "character device" $fuzzypid export-header c.toml --out full
  refused "character device" $fuzzypid export-rules c.toml --surface full
  refused "character device" "$rt_loop" --period-ms 0 --ticks 3 --csv full
  refused "character device" "$sim_ab" --quiet --out full
  [ -c full ] || fail "the device node was replaced: $(ls -l full)"
fi
[ -p fifo ] || fail "the FIFO was replaced: $(ls -l fifo)"
cmp -s c.toml c.orig || fail "an input controller file was changed"
cmp -s cond.toml cond.orig || fail "an input condition file was changed"
[ -h link.toml ] || fail "link.toml is no longer a link"
[ -z "$(ls -A ro)$(ls -A folder)" ] || fail "something was written: $(ls -A ro) $(ls -A folder)"
ls -A | grep -q '\.tmp' && fail "temporary left: $(ls -A)"
[ -e x.fll ] && fail "export-rules wrote its rule file although another output was refused"

# A base with a rule file and an --out without a folder: the rule file is named relative to the
# current folder (this used to fail after the whole budget with a filesystem error).
"$fuzzypid" tune --family fuzzy --base "$src/tests/sim/data/engine_fuzzy.toml" --conditions cond.toml \
  --budget 40 --population 20 --threads 1 --quiet --out name.toml >out 2>err ||
  fail "tune --base with a rule file --out name.toml: $(cat err)"
grep -q '^rule_file = ".*rulebases/paper.fll"' name.toml || fail "rule file: $(grep rule_file name.toml)"
rm -f name.toml

# The file standard output goes to is no output either (directly or through /dev/stdout).
ln -s /dev/stdout to_stdout.csv
for csv in log.txt to_stdout.csv; do
  : >log.txt
  "$rt_loop" --period-ms 0 --ticks 3 --csv "$csv" >log.txt 2>err
  code=$?
  [ "$code" -eq 2 ] || fail "--csv $csv > log.txt: exit $code: $(cat err)"
  grep -q "standard output" err || fail "--csv $csv > log.txt: $(cat err)"
done
rm -f log.txt to_stdout.csv

# Accepted: a symbolic link to a regular file is followed (the link stays a link).
echo old >real.hpp
ln -s real.hpp out_link.hpp
"$fuzzypid" export-header c.toml --out out_link.hpp 2>err || fail "export through a link: $(cat err)"
[ -h out_link.hpp ] && grep -q '#pragma once' real.hpp || fail "the link was not followed"

# A failed write (RLIMIT_FSIZE of 512 bytes; SIGXFSZ ignored so the write returns EFBIG) keeps the
# previous header and leaves no temporary.
echo previous >prev.hpp
(trap '' XFSZ; ulimit -f 1; exec "$fuzzypid" export-header c.toml --out prev.hpp) 2>err
code=$?
[ "$code" -eq 1 ] || fail "export-header on a full file system: exit $code: $(cat err)"
grep -q 'File too large' err || fail "no reason given: $(cat err)"
[ "$(cat prev.hpp)" = previous ] || fail "the previous header was destroyed"
ls -A | grep -q '\.tmp' && fail "temporary left after a failed write: $(ls -A)"
# A full disk, where a private mount namespace and a 64 KiB tmpfs are available (root): ENOSPC
# keeps the previous header and controller file. The mount vanishes with the namespace, whatever
# happens to this script.
mkdir full_disk
if unshare --mount sh -c "mount -t tmpfs -o size=64k tmpfs '$work/full_disk'" 2>/dev/null; then
  unshare --mount sh -c '
    set -u
    cd "$1" && mount -t tmpfs -o size=64k tmpfs full_disk && cd full_disk || exit 3
    echo previous >h.hpp
    dd if=/dev/zero of=fill bs=4k count=15 2>/dev/null
    "$2" export-header "$3/controllers/paper_fuzzy.toml" --allow-uncertified --out h.hpp 2>"$1/err"
    [ $? -eq 1 ] && grep -q "No space left on device" "$1/err" || { cat "$1/err"; exit 4; }
    "$2" tune --family pid --conditions "$3/tuning/robust.toml" --budget 40 --population 20 \
      --threads 1 --quiet --out h.hpp 2>"$1/err"
    [ $? -eq 1 ] && grep -q "No space left on device" "$1/err" || { cat "$1/err"; exit 5; }
    [ "$(cat h.hpp)" = previous ] || exit 6
    [ "$(ls -A)" = "fill
h.hpp" ] || { ls -A; exit 7; }
  ' sh "$work" "$fuzzypid" "$src" || fail "full disk: case $?"
else
  echo "note: no private tmpfs (needs root): the full-disk case is not checked"
fi
echo ok
