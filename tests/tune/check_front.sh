#!/bin/sh
# `fuzzypid tune --objectives ... --front-out DIR` from the shell (tests/tune/CMakeLists.txt):
#   points     the front's points are mutually non-dominated on the objectives front.csv reports,
#              each names its controller file, and each file records its objectives; sim_ab
#              --controller DIR runs every point on the held-out conditions;
#   resume     a tune stopped by SIGTERM exits 143 with its state checkpointed and no front
#              written, and resumed from the checkpoint ends with the same files as an
#              uninterrupted run;
#   mpi        mpirun -np 2 gives the same front, byte for byte, as one process (and the
#              one-objective tuner the same file); a rank killed mid-search ends the job with an
#              error naming it and no front written, and the last checkpoint resumes to the same
#              front.
# Usage: check_front.sh CASE FUZZYPID CONDITIONS WORKDIR [SIM_AB (points) | MPIRUN (mpi)]
set -eu
case_name=$1
fuzzypid=$2
conditions=$3
work=$4/front_$case_name
tool=${5:-}
rm -rf "$work"
mkdir -p "$work"
cd "$work"
fail() {
  echo "check_front.sh $case_name: $*" >&2
  exit 1
}

# Every row of DIR/front.csv: its file exists and records a front; no row dominates another.
check_points() {
  dir=$1
  [ -f "$dir/front.csv" ] || fail "$dir/front.csv missing"
  head -1 "$dir/front.csv" | grep -q '^point,file,itae,effort,overshoot,validation_itae,' ||
    fail "unexpected header: $(head -1 "$dir/front.csv")"
  rows=$(($(wc -l <"$dir/front.csv") - 1))
  [ "$rows" -ge 2 ] || fail "a front of $rows points"
  [ "$(ls "$dir"/point_*.toml | wc -l)" -eq "$rows" ] || fail "point files and rows differ"
  tail -n +2 "$dir/front.csv" | while IFS=, read -r point file rest; do
    [ -f "$dir/$file" ] || fail "row $point names $file, which is missing"
    grep -q '^front = \[' "$dir/$file" || fail "$file records no front"
  done
  # Columns 3-5 are the training objectives, all minimised.
  awk -F, 'NR > 1 { n++; for (j = 3; j <= 5; j++) v[n, j] = $j + 0 }
    END {
      for (a = 1; a <= n; a++) for (b = 1; b <= n; b++) {
        if (a == b) continue
        le = 1; lt = 0
        for (j = 3; j <= 5; j++) { if (v[a, j] > v[b, j]) le = 0; if (v[a, j] < v[b, j]) lt = 1 }
        if (le && lt) { printf "point %d dominates point %d\n", a - 1, b - 1; bad = 1 }
      }
      exit bad
    }' "$dir/front.csv" || fail "the front has dominated points"
}

# Waits until the checkpoint FILE holds a generation after the first population.
wait_for_generation() {
  tries=0
  until grep -q '^generation [1-9]' "$1" 2>/dev/null; do
    tries=$((tries + 1))
    [ "$tries" -lt 1200 ] || fail "no checkpoint in $1 after 60 s"
    sleep 0.05
  done
}

args="tune --family pid --objectives itae,effort,overshoot --conditions $conditions --validation 4
      --population 20 --seed 5 --quiet"
case "$case_name" in
points)
  # shellcheck disable=SC2086
  "$fuzzypid" $args --budget 400 --threads 2 --front-out front >out.txt
  check_points front
  grep -q '^front of family pid: [0-9]* points, 400 evaluations' out.txt || fail "no summary"
  "$tool" --controller front --conditions "$conditions" --set held-out --out held_out --quiet
  ran=$(awk -F, 'NR > 1 { print $2 }' held_out/metrics.csv | sort -u | wc -l)
  rows=$(($(wc -l <front/front.csv) - 1))
  [ "$ran" -eq "$rows" ] || fail "sim_ab ran $ran controllers of a front of $rows points"
  grep -q '^[^,]*,front_point_000,' held_out/metrics.csv || fail "no row of front_point_000"
  ;;
resume)
  # shellcheck disable=SC2086
  "$fuzzypid" $args --budget 1000 --threads 2 --front-out whole >/dev/null
  # shellcheck disable=SC2086
  "$fuzzypid" $args --budget 1000 --threads 1 --front-out part --checkpoint state.txt \
    >/dev/null 2>stopped.err &
  pid=$!
  # Stop it once a generation after the first population is saved.
  wait_for_generation state.txt
  kill -TERM "$pid"
  code=0
  wait "$pid" || code=$?
  [ "$code" -eq 143 ] || fail "stopped run exited $code, expected 143: $(cat stopped.err)"
  grep -q 'resume with --resume\|--resume state.txt to continue' stopped.err || fail "no hint"
  [ ! -e part ] || fail "a stopped run wrote its front"
  stopped_at=$(sed -n 's/^generation //p' state.txt)
  [ "$stopped_at" -lt 49 ] || fail "the run ended before it was stopped"
  # shellcheck disable=SC2086
  "$fuzzypid" $args --budget 1000 --threads 2 --front-out part --checkpoint state.txt \
    --resume state.txt >/dev/null
  diff -r whole part || fail "the resumed front differs from the uninterrupted one"
  check_points part
  # A checkpoint of another search is refused, naming the option.
  code=0
  # shellcheck disable=SC2086
  "$fuzzypid" $args --budget 600 --front-out other --resume state.txt 2>other.err ||
    code=$?
  [ "$code" -eq 1 ] || fail "a foreign checkpoint exited $code"
  grep -q 'written by a tune with budget 1000, this one has 600' other.err || fail "$(cat other.err)"
  ;;
mpi)
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
  # shellcheck disable=SC2086
  "$fuzzypid" $args --budget 400 --threads 2 --front-out one >/dev/null
  # shellcheck disable=SC2086
  "$tool" -np 2 --oversubscribe "$fuzzypid" $args --budget 400 --threads 1 --front-out two \
    >/dev/null
  diff -r one two || fail "two ranks gave another front"
  check_points two
  single="tune --family pid --conditions $conditions --budget 200 --population 20 --seed 5 --quiet"
  # shellcheck disable=SC2086
  "$fuzzypid" $single --threads 2 --out one.toml
  # shellcheck disable=SC2086
  "$tool" -np 2 --oversubscribe "$fuzzypid" $single --threads 1 --out two.toml
  cmp one.toml two.toml || fail "two ranks gave another one-objective result"
  # Rank 1 killed once a generation is saved.
  # shellcheck disable=SC2086
  "$fuzzypid" $args --budget 1000 --threads 2 --front-out whole >/dev/null
  # shellcheck disable=SC2086
  "$tool" -np 2 --oversubscribe "$fuzzypid" $args --budget 1000 --threads 1 --front-out lost \
    --checkpoint lost.txt >/dev/null 2>lost.err &
  job=$!
  wait_for_generation lost.txt
  for p in $(pgrep -f -- "--front-out lost"); do
    if tr '\0' '\n' <"/proc/$p/environ" 2>/dev/null | grep -qx 'OMPI_COMM_WORLD_RANK=1'; then
      kill -9 "$p"
    fi
  done
  code=0
  wait "$job" || code=$?
  [ "$code" -ne 0 ] || fail "a job that lost a rank exited 0"
  grep -q 'rank 1' lost.err || fail "no rank named: $(cat lost.err)"
  [ ! -e lost ] || fail "a job that lost a rank wrote its front"
  # shellcheck disable=SC2086
  "$tool" -np 2 --oversubscribe "$fuzzypid" $args --budget 1000 --threads 1 --front-out lost \
    --checkpoint lost.txt --resume lost.txt >/dev/null
  diff -r whole lost || fail "the front resumed after a lost rank differs"
  ;;
*)
  fail "unknown case"
  ;;
esac
echo "check_front.sh $case_name: ok"
