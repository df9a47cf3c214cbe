#!/bin/sh
# rt_loop's exit codes, its --csv file (opened before the run, complete or absent), --dt,
# --require-rt and --max-overruns. Usage: check_rt_loop.sh <path to rt_loop>
set -u
rt_loop=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
# expect CODE ARGS...: runs rt_loop, stdout in $work/out, stderr in $work/err.
expect() {
  want=$1
  shift
  "$rt_loop" "$@" >"$work/out" 2>"$work/err"
  got=$?
  [ "$got" -eq "$want" ] || fail "rt_loop $*: exit $got, expected $want: $(cat "$work/err")"
}

# Bad usage exits 2 (not 1, not a run).
for args in "--ticks -1" "--ticks 18446744073709551616" "--period-ms nan" "--period-ms inf" \
            "--dt 0" "--dt 2" "--controller lqr" "--max-overruns -3" "--bogus" "--period-ms 0.01" \
            "--period-ms 20000"; do
  # shellcheck disable=SC2086
  expect 2 $args
  grep -q '^ticks_run' "$work/out" && fail "rt_loop $args ran"
done

# The controller period follows the tick period unless --dt is given; 50 ms when free-running.
expect 0 --period-ms 5 --ticks 3
grep -q 'controller dt 5.000 ms' "$work/out" || fail "dt with --period-ms 5: $(head -1 "$work/out")"
expect 0 --period-ms 5 --dt 0.01 --ticks 3
grep -q 'controller dt 10.000 ms' "$work/out" || fail "--dt 0.01: $(head -1 "$work/out")"
expect 0 --period-ms 0 --ticks 3
grep -q 'controller dt 50.000 ms' "$work/out" || fail "free-running: $(head -1 "$work/out")"
for figure in 'ticks_run: 3 ticks' 'overruns: 0 ticks' 'compute_us: min' 'max_abs_error_rad: .* rad' \
              'page_faults_in_loop: minor [0-9]*, major [0-9]*' 'allocations_in_loop: 0'; do
  grep -q "^$figure" "$work/out" || fail "no '$figure' in: $(cat "$work/out")"
done
expect 0 --period-ms 1 --ticks 5
grep -q '^period_error_us: min' "$work/out" || fail "no period error: $(cat "$work/out")"

# --loop plays the path back and forth: over three passes the largest error is that of one pass
# (a restart from B straight back to A would add a jump of about 0.6 rad).
expect 0 --period-ms 0 --controller fuzzy
one=$(sed -n 's/^max_abs_error_rad: \([0-9.e+-]*\) rad$/\1/p' "$work/out")
expect 0 --period-ms 0 --controller fuzzy --loop --ticks 303
looped=$(sed -n 's/^max_abs_error_rad: \([0-9.e+-]*\) rad$/\1/p' "$work/out")
[ -n "$one" ] && [ -n "$looped" ] || fail "no max_abs_error_rad: $(cat "$work/out")"
awk -v a="$one" -v b="$looped" 'BEGIN { exit !(b <= 1.5 * a && b < 0.2) }' ||
  fail "--loop: max error $looped rad against $one rad for one pass"

# --csv to an unwritable place is a usage error before the run (tests/cli/check_outputs.sh has
# the other refused paths); a complete file appears only at the end.
expect 2 --period-ms 0 --ticks 1000 --csv "$work/missing/ticks.csv"
grep -q '^ticks_run' "$work/out" && fail "ran although the CSV cannot be written"
grep -q "^rt_loop: --csv: .*missing/ticks.csv.*No such file or directory" "$work/err" ||
  fail "no reason: $(cat "$work/err")"
expect 0 --period-ms 0 --ticks 50 --csv "$work/ticks.csv"
[ "$(head -1 "$work/ticks.csv")" = "tick,wakeup_latency_ns,period_error_ns,compute_ns" ] ||
  fail "CSV header: $(head -1 "$work/ticks.csv")"
[ "$(wc -l <"$work/ticks.csv")" -eq 51 ] || fail "CSV rows: $(wc -l <"$work/ticks.csv")"
[ "$(ls -A "$work")" = "err
out
ticks.csv" ] || fail "left beside the CSV: $(ls -A "$work")"

# A 1 us period cannot be held: every tick overruns, so --max-overruns 0 fails the run.
expect 1 --period-ms 0.001 --dt 0.05 --ticks 20 --max-overruns 0
grep -q 'more overruns than --max-overruns' "$work/err" || fail "$(cat "$work/err")"
expect 0 --period-ms 0.001 --dt 0.05 --ticks 20 --max-overruns 20

# A refused SCHED_FIFO is a warning, and with --require-rt an error. Refusal is provoked by an
# rtprio limit of 0 and, for root, by dropping CAP_SYS_NICE.
drop=""
if setpriv --bounding-set -sys_nice --inh-caps -sys_nice true 2>/dev/null; then
  drop="setpriv --bounding-set -sys_nice --inh-caps -sys_nice"
fi
$drop prlimit --rtprio=0:0 "$rt_loop" --ticks 2 --period-ms 1 --fifo 10 >"$work/out" 2>"$work/err" ||
  fail "refused FIFO without --require-rt: $(cat "$work/err")"
if grep -q '^scheduler: SCHED_FIFO priority' "$work/out"; then
  echo "note: SCHED_FIFO was granted despite rtprio 0 (capabilities kept): refusal not checked"
else
  grep -q 'warning: SCHED_FIFO refused' "$work/err" || fail "no warning: $(cat "$work/err")"
  $drop prlimit --rtprio=0:0 "$rt_loop" --ticks 2 --period-ms 1 --fifo 10 --require-rt \
    >"$work/out" 2>"$work/err" && fail "refused FIFO with --require-rt exited 0"
  grep -q 'error: SCHED_FIFO refused' "$work/err" || fail "no error: $(cat "$work/err")"
  grep -q '^ticks_run' "$work/out" && fail "ran although --require-rt was refused"
fi

# SIGTERM and SIGHUP stop the run as SIGINT does: the summary, the complete CSV (one row per tick
# run), exit 0 and no temporary file left.
mkdir "$work/sig"
# start_run: rt_loop in the background writing $work/sig/ticks.csv; returns once the loop runs.
start_run() {
  "$rt_loop" --period-ms 5 --ticks 100000 --csv "$work/sig/ticks.csv" >"$work/out" 2>"$work/err" &
  pid=$!
  n=0
  while ! grep -q '^scheduler' "$work/out" && [ "$n" -lt 200 ]; do
    sleep 0.05
    n=$((n + 1))
  done
  sleep 0.3
}
for sig in TERM HUP INT; do
  rm -f "$work/sig/ticks.csv"
  start_run
  kill -s "$sig" "$pid"
  wait "$pid"
  code=$?
  [ "$code" -eq 0 ] || fail "SIG$sig: exit $code: $(cat "$work/err")"
  grep -q '^interrupted: stopped at the next tick' "$work/out" || fail "SIG$sig: $(cat "$work/out")"
  grep -q '^allocations_in_loop: 0' "$work/out" || fail "SIG$sig: no summary: $(cat "$work/out")"
  rows=$(sed -n 's/^ticks_run: \([0-9]*\) ticks$/\1/p' "$work/out")
  [ -n "$rows" ] && [ "$rows" -gt 0 ] || fail "SIG$sig: ticks_run: $(cat "$work/out")"
  [ "$(wc -l <"$work/sig/ticks.csv")" -eq $((rows + 1)) ] ||
    fail "SIG$sig: $(wc -l <"$work/sig/ticks.csv") CSV lines for $rows ticks"
  [ "$(ls -A "$work/sig")" = ticks.csv ] || fail "SIG$sig: left: $(ls -A "$work/sig")"
done
# A run killed outright (SIGKILL) leaves its temporary .ticks.csv.rt_loop.<pid>.tmp; the next run
# writing the same CSV removes it, as the process is gone.
start_run
kill -s KILL "$pid"
wait "$pid"
[ -e "$work/sig/.ticks.csv.rt_loop.$pid.tmp" ] || fail "no temporary named by pid: $(ls -A "$work/sig")"
expect 0 --period-ms 0 --ticks 5 --csv "$work/sig/ticks.csv"
[ "$(ls -A "$work/sig")" = ticks.csv ] || fail "stale temporary kept: $(ls -A "$work/sig")"

# Output that cannot be written is an error, on standard error too (the run's summary line lost).
"$rt_loop" --period-ms 0 --ticks 3 >/dev/full 2>"$work/err" && fail "> /dev/full exited 0"
"$rt_loop" --period-ms 0 --ticks 3 >/dev/null 2>/dev/full
[ $? -eq 1 ] || fail "2> /dev/full did not exit 1"
echo ok
