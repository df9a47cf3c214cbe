#!/bin/sh
# Every tool's inputs follow one contract (docs/robustness.md, "Inputs"):
#   fifo_inputs_are_refused      a FIFO, a device or a folder given as any input file (option, key
#                                of a condition file, rule file of a controller) is refused by its
#                                kind, naming the file, before it is opened: exit 1 within 10 s
#                                (a FIFO with no writer used to block the tool forever);
#   one_writer_per_output        while another run writes an output file (its lock is held), tune
#                                and rt_loop exit 1 naming the file and leave it alone;
#   empty_values_are_refused     '' is never "the default": every option and condition key refuses
#                                it, naming itself;
#   init_rule_file_is_rebased    tune --init writes the start's rule file relative to the result's
#                                folder, so the result loads the same rule file from anywhere.
# Usage: check_inputs.sh <fuzzypid> <rt_loop> <sim_ab> <source dir> <case>
set -u
fuzzypid=$1
rt_loop=$2
sim_ab=$3
src=$4
case_name=$5
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
fail() {
  echo "FAIL ($case_name): $*" >&2
  exit 1
}
# expect CODE PATTERN CMD...: exit CODE within 10 s (124: it blocked), PATTERN (grep -E) on stderr.
expect() {
  want=$1
  pattern=$2
  shift 2
  timeout 10 "$@" </dev/null >out 2>err
  code=$?
  [ "$code" -ne 124 ] || fail "$*: still running after 10 s (blocked on an input?)"
  [ "$code" -eq "$want" ] || fail "$*: exit $code, expected $want: $(cat err)"
  [ -z "$pattern" ] || grep -Eq -- "$pattern" err || fail "$*: no '$pattern' in: $(cat err)"
}

tiny="--budget 14 --population 7 --threads 1 --quiet"
tune="$fuzzypid tune --family pid $tiny"
printf '[sets.training]\nconditions = [ { name = "n", payload_scale = 1.0 } ]\n' >cond.toml
sed 's|^rule_file = .*|rule_file = "rules.fll"|' "$src/tests/sim/data/engine_fuzzy.toml" >rule_ctl.toml
cp "$src/rulebases/paper.fll" rules.fll

case $case_name in
  fifo_inputs_are_refused)
    mkfifo fifo fifo.fll fifo.fis fifo.fcl fifo.toml
    mkdir folder.fll
    fifo_msg="'fifo' is a FIFO, not a regular file"
    expect 1 "URDF: $fifo_msg" "$fuzzypid" fk --urdf fifo
    expect 1 "URDF: $fifo_msg" "$fuzzypid" ik --urdf fifo
    expect 1 "URDF: $fifo_msg" "$sim_ab" --quiet --urdf fifo --out o
    expect 1 "path: $fifo_msg" "$sim_ab" --quiet --path fifo --out o
    expect 1 "URDF: $fifo_msg" "$rt_loop" --period-ms 0 --ticks 3 --urdf fifo
    expect 1 "path: $fifo_msg" "$rt_loop" --period-ms 0 --ticks 3 --path fifo
    expect 1 "--init: .*'fifo.toml' is a FIFO" $tune --conditions cond.toml --init fifo.toml --out r.toml
    expect 1 "'fifo.toml' is a FIFO" $tune --conditions cond.toml --base fifo.toml --out r.toml
    expect 1 "'fifo.toml' is a FIFO" $tune --conditions fifo.toml --out r.toml
    expect 1 "'fifo.toml' is a FIFO" "$sim_ab" --quiet --conditions fifo.toml --out o
    expect 1 "'fifo.toml' is a FIFO" "$sim_ab" --quiet --controller fifo.toml --out o
    expect 1 "'fifo.toml' is a FIFO" "$rt_loop" --period-ms 0 --ticks 3 --controller fifo.toml
    # A condition file's urdf and path keys.
    printf '[sets.training]\nurdf = "fifo"\nconditions = [ { name = "n" } ]\n' >urdf_fifo.toml
    expect 1 "condition n: .*URDF: $fifo_msg" $tune --conditions urdf_fifo.toml --out r.toml
    printf '[sets.training]\npath = "fifo"\nconditions = [ { name = "n" } ]\n' >path_fifo.toml
    expect 1 "condition n: path: $fifo_msg" $tune --conditions path_fifo.toml --out r.toml
    # A controller's rule_file.
    sed 's|^rule_file = .*|rule_file = "fifo.fll"|' rule_ctl.toml >fifo_rules.toml
    expect 1 "'fifo.fll' is a FIFO" "$sim_ab" --quiet --controller fifo_rules.toml --out o
    expect 1 "'fifo.fll' is a FIFO" "$fuzzypid" export-header fifo_rules.toml
    expect 1 "'fifo.fll' is a FIFO" $tune --conditions cond.toml --init fifo_rules.toml --out r.toml
    # The commands' file arguments.
    expect 1 "'fifo.toml' is a FIFO" "$fuzzypid" export-header fifo.toml
    expect 1 "'fifo.toml' is a FIFO" "$fuzzypid" export-rules fifo.toml --out x.fll
    expect 1 "'fifo.fll' is a FIFO" "$fuzzypid" check-rules fifo.fll
    expect 1 "'fifo.fis' is a FIFO" "$fuzzypid" eval --fis fifo.fis
    expect 1 "'fifo.fll' is a FIFO" "$fuzzypid" eval --fll fifo.fll
    expect 1 "'fifo.fcl' is a FIFO" "$fuzzypid" eval --fcl fifo.fcl
    # Devices and folders too, by kind.
    expect 1 "'/dev/null' is a character device, not a regular file" "$fuzzypid" fk --urdf /dev/null
    expect 1 "'/dev/zero' is a character device, not a regular file" "$sim_ab" --quiet \
      --path /dev/zero --out o
    expect 1 "'folder.fll' is a directory, not a regular file" "$fuzzypid" check-rules folder.fll
    [ -e o ] && fail "an output folder was written"
    [ -e r.toml ] && fail "a tuning result was written"
    true
    ;;
  one_writer_per_output)
    # Another run holds the lock of r.toml (flock on .r.toml.lock, as the tools take it).
    exec 9>.r.toml.lock
    flock -n 9 || fail "cannot take the lock"
    expect 1 "the output file 'r.toml' is being written by another process" \
      $tune --conditions cond.toml --out r.toml
    [ -e r.toml ] && fail "tune wrote r.toml while another run was writing it"
    expect 1 "the output file 'r.toml' is being written by another process" \
      "$rt_loop" --period-ms 0 --ticks 3 --csv r.toml
    [ -e r.toml ] && fail "rt_loop wrote r.toml while another run was writing it"
    exec 9>&-
    # Free again: the run writes the file, and leaves no lock file or temporary behind.
    expect 0 "" $tune --conditions cond.toml --out r.toml
    grep -q '^family = "pid"' r.toml || fail "tune result: $(cat r.toml)"
    leftovers=$(ls -A | grep '^\.r\.toml')
    [ -z "$leftovers" ] || fail "left behind: $leftovers"
    # Two tune runs: the second is refused while the first spends its budget; the first, stopped
    # by SIGTERM (a background job of sh ignores SIGINT), leaves its lock and temporary behind
    # neither, and the previous r.toml untouched.
    cp r.toml r.before
    $fuzzypid tune --family pid --budget 100000000 --population 20 --threads 1 --quiet \
      --conditions cond.toml --out r.toml >/dev/null 2>&1 &
    first=$!
    n=0
    while [ ! -e .r.toml.lock ] && [ "$n" -lt 100 ]; do sleep 0.05; n=$((n + 1)); done
    expect 1 "the output file 'r.toml' is being written by another process" \
      $tune --conditions cond.toml --out r.toml
    kill -s TERM "$first"
    wait "$first"
    code=$?
    [ "$code" -eq 143 ] || fail "the first tune: exit $code, expected death by SIGTERM (143)"
    leftovers=$(ls -A | grep '^\.r\.toml')
    [ -z "$leftovers" ] || fail "left behind by the stopped run: $leftovers"
    cmp -s r.toml r.before || fail "the stopped run changed r.toml"
    ;;
  empty_values_are_refused)
    for opt in --urdf --base-link --tip-link --path; do
      expect 2 "$opt: empty" "$sim_ab" --quiet "$opt" '' --out o
      expect 2 "$opt: empty" "$rt_loop" --period-ms 0 --ticks 3 "$opt" ''
    done
    expect 2 "--urdf: empty value" "$fuzzypid" fk --urdf ''
    expect 2 "--urdf: empty value" "$fuzzypid" ik --urdf ''
    expect 2 "--init: empty value" $tune --conditions cond.toml --init '' --out r.toml
    expect 2 "--base: empty value" $tune --conditions cond.toml --base '' --out r.toml
    expect 2 "--set: empty value" $tune --conditions cond.toml --set '' --out r.toml
    expect 2 "--conditions: empty value" $tune --conditions '' --out r.toml
    expect 2 "--controller: empty value" "$sim_ab" --quiet --controller '' --out o
    expect 2 "--fis: empty value" "$fuzzypid" eval --fis ''
    expect 2 "file: empty value" "$fuzzypid" export-header ''
    expect 2 "FILE: empty value" "$fuzzypid" check-rules ''
    for key in urdf tip_link base_link path; do
      printf '[sets.training]\n%s = ""\nconditions = [ { name = "n" } ]\n' "$key" >empty.toml
      expect 1 "empty.toml:2:[0-9]+: '$key' is empty" $tune --conditions empty.toml --out r.toml
      expect 1 "empty.toml:2:[0-9]+: '$key' is empty" "$sim_ab" --quiet --conditions empty.toml \
        --out o
    done
    sed 's|^rule_file = .*|rule_file = ""|' rule_ctl.toml >empty_rules.toml
    expect 1 "empty_rules.toml:[0-9]+:[0-9]+: 'rule_file' is empty" "$fuzzypid" export-header \
      empty_rules.toml
    [ -e o ] && fail "an output folder was written"
    [ -e r.toml ] && fail "a tuning result was written"
    true
    ;;
  init_rule_file_is_rebased)
    # The start names its rule file relative to its own folder (start/); the tune runs from run/
    # and writes into result/; the result is read from the work folder. Decoy rule files of the
    # same name in run/ and result/ are not rule bases: loading either fails.
    mkdir start run result
    mv rule_ctl.toml rules.fll start/
    echo 'not a rule base' >run/rules.fll
    echo 'not a rule base' >result/rules.fll
    (cd run && $fuzzypid tune --family fuzzy $tiny --conditions ../cond.toml --init ../start/rule_ctl.toml \
      --out ../result/tuned.toml) 2>err || fail "tune: $(cat err)"
    grep -qx 'rule_file = "../start/rules.fll"  # relative to this file'"'"'s folder' \
      result/tuned.toml || fail "rule_file: $(grep rule_file result/tuned.toml)"
    grep -qx 'conditions = "../cond.toml"' result/tuned.toml ||
      fail "conditions: $(grep '^conditions' result/tuned.toml)"
    grep -q '^init = "../start/rule_ctl.toml"' result/tuned.toml ||
      fail "init: $(grep '^init' result/tuned.toml)"
    # Read from a third folder, it evaluates the start's rule base (export-header embeds it).
    expect 0 "" "$fuzzypid" export-header result/tuned.toml --allow-uncertified
    grep -q "rule base of ../start/rules.fll (2 inputs, 3 outputs, 49 rules" out ||
      fail "exported rule base: $(grep 'rule base of' out)"
    # And it tunes on: --base of the result, from yet another folder.
    (cd start && $fuzzypid tune --family fuzzy $tiny --conditions ../cond.toml --base ../result/tuned.toml \
      --out again.toml) 2>err || fail "tune --base result: $(cat err)"
    grep -qx 'rule_file = "rules.fll"  # relative to this file'"'"'s folder' start/again.toml ||
      fail "rule_file of the second result: $(grep rule_file start/again.toml)"
    ;;
  *)
    fail "unknown case"
    ;;
esac
exit 0
