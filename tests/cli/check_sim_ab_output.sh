#!/bin/sh
# sim_ab's output directory is replaced as a whole, locked while written, and never left with
# temporaries. Usage: check_sim_ab_output.sh <path to sim_ab>
set -u
sim_ab=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() {
  echo "FAIL: $*" >&2
  exit 1
}

"$sim_ab" --quiet --out "$work/out" 2>"$work/err" || fail "first run: $(cat "$work/err")"
[ "$(ls -A "$work")" = "err
out" ] || fail "beside the output: $(ls -A "$work")"
cp "$work/out/metrics.csv" "$work/metrics.first"
echo plot >"$work/out/fig.png"

# A second writer is refused while the directory is locked (here by flock(1) on the same lock
# file), and the locked set is left as it was.
flock "$work/.out.lock" "$sim_ab" --quiet --initial-error 0.1 --out "$work/out" \
  2>"$work/err" && fail "a run into a locked directory succeeded"
grep -q "is being written by another process" "$work/err" || fail "locked: $(cat "$work/err")"
cmp -s "$work/out/metrics.csv" "$work/metrics.first" || fail "the locked set changed"

# The next run replaces the set and keeps the other files; nothing hidden is left anywhere.
"$sim_ab" --quiet --initial-error 0.1 --out "$work/out" 2>"$work/err" ||
  fail "second run: $(cat "$work/err")"
cmp -s "$work/out/metrics.csv" "$work/metrics.first" && fail "the set was not replaced"
[ "$(cat "$work/out/fig.png")" = plot ] || fail "fig.png was not kept"
ls -A "$work" | grep -q '^\.' && fail "hidden files beside the output: $(ls -A "$work")"
ls -A "$work/out" | grep -q '^\.' && fail "hidden files in the output: $(ls -A "$work/out")"

# A directory that holds a subdirectory is not replaced.
mkdir "$work/out/keep"
"$sim_ab" --quiet --out "$work/out" 2>"$work/err" && fail "replaced a directory with a subdirectory"
[ -d "$work/out/keep" ] || fail "the subdirectory is gone"
echo "ok"
