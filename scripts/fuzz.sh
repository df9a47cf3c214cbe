#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) in build-fuzz/ and runs each for a bounded
# time from its seeds in fuzz/corpus/<name>/ and the project's data files (see below):
#   fis, fll, fcl  the .fis / .fll / .fcl rule-file readers
#   csv            the command-line tools' CSV reader
#   urdf           the URDF loader (robot::RobotModel::load)
#   sim_ab_args    sim_ab's command-line parser
#   rt_loop_args   rt_loop's command-line parser and its --csv output path checks
#   controller_file  the controller-file loader (TOML)
#   FUZZ_SECONDS   time per target (default 30)
#   FUZZ_TARGETS   space-separated subset of the names above (default: all)
# Exits non-zero on any crash, leak, timeout or sanitizer report; the failing input is left in
# build-fuzz/ (crash-*, leak-*, timeout-*). Prints the executions run per target.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${FUZZ_SECONDS:-30}"
targets="${FUZZ_TARGETS:-fis fll fcl csv urdf sim_ab_args rt_loop_args controller_file}"
CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DFUZZYPID_BUILD_FUZZERS=ON -DFUZZYPID_BUILD_TESTS=OFF -DFUZZYPID_BUILD_APPS=OFF \
  -DFUZZYPID_BUILD_BENCH=OFF -DFUZZYPID_WITH_ROBOT=ON >/dev/null
build_targets=()
for name in ${targets}; do build_targets+=("fuzz_${name}"); done
cmake --build build-fuzz -j "$(nproc)" --target "${build_targets[@]}"

summary=()
for name in ${targets}; do
  work="build-fuzz/corpus-${name}"
  log="build-fuzz/fuzz_${name}.log"
  mkdir -p "${work}"
  echo "fuzz_${name}: ${seconds} s"
  max_len=8192
  if [ "${name}" = urdf ]; then max_len=16384; fi
  if [ "${name}" = sim_ab_args ] || [ "${name}" = rt_loop_args ]; then max_len=512; fi
  # New inputs go to the work corpus; the checked-in seeds are only read. Artifacts (crash-*,
  # leak-*, timeout-*) land in build-fuzz/.
  # The project's own data files are seeds as they are, not copies (libFuzzer reads directories
  # recursively and writes only to the first): rule files of every format for each rule-file
  # reader, the URDFs and the loader's test robots, the shipped controller and condition files
  # and the simulation's and the tuner's test data (the target reads condition files too).
  shared=()
  case "${name}" in
    fis | fll | fcl) shared=(../rulebases ../tests/rulefile/data) ;;
    urdf) shared=(../urdf ../tests/robot/data) ;;
    controller_file) shared=(../controllers ../tuning ../tests/sim/data ../tests/tune/data) ;;
  esac
  status=0
  (cd build-fuzz && "bin/fuzz_${name}" -max_total_time="${seconds}" -max_len="${max_len}" \
    -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 "corpus-${name}" "../fuzz/corpus/${name}" \
    "${shared[@]}") \
    >"${log}" 2>&1 || status=$?
  tail -n 12 "${log}"
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "${log}" | tail -n 1)
  summary+=("fuzz_${name}: ${execs:-?} executions in ${seconds} s, exit ${status}")
  if [ "${status}" -ne 0 ]; then
    echo "fuzz_${name} FAILED (see ${log})" >&2
    printf '%s\n' "${summary[@]}"
    exit 1
  fi
done
printf '%s\n' "${summary[@]}"
