#!/bin/sh
# Runs a command and passes only when it exits with the expected code AND its output (stdout and
# stderr together) matches every pattern. ctest's PASS_REGULAR_EXPRESSION ignores the exit code
# and WILL_FAIL accepts any non-zero one; ctest cases use this instead.
# Usage: expect.sh CODE [PATTERN...] -- COMMAND [ARGS...]
# PATTERNs are extended regular expressions (grep -E), each matched against some line.
set -u
if [ $# -lt 3 ]; then
  echo "usage: expect.sh CODE [PATTERN...] -- COMMAND [ARGS...]" >&2
  exit 2
fi
want=$1
shift
patterns=$(mktemp)
output=$(mktemp)
trap 'rm -f "$patterns" "$output"' EXIT
while [ $# -gt 0 ] && [ "$1" != -- ]; do
  printf '%s\n' "$1" >>"$patterns"
  shift
done
[ $# -gt 1 ] || { echo "expect.sh: no command after --" >&2; exit 2; }
shift
"$@" >"$output" 2>&1
got=$?
cat "$output"
status=0
if [ "$got" -ne "$want" ]; then
  echo "expect.sh: exit code $got, expected $want" >&2
  status=1
fi
while IFS= read -r pattern; do
  if ! grep -Eq -- "$pattern" "$output"; then
    echo "expect.sh: no line matches '$pattern'" >&2
    status=1
  fi
done <"$patterns"
exit "$status"
