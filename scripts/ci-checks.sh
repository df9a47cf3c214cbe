#!/usr/bin/env bash
# CI hardening stages, run by .ci/run after scripts/test.sh (docs/robustness.md explains each):
#   1. asan      GCC build with ASan + UBSan (-fno-sanitize-recover=all) and -Werror on the
#                project's own targets, in build-asan/; the whole ctest suite runs under it.
#   2. werror    covered by stage 1 (FUZZYPID_WERROR=ON in the same build).
#   3. tidy      clang-tidy (.clang-tidy) over the project's .cpp files and, through the
#                standalone-header test sources, every public core header.
#   4. cppcheck  warning, performance, portability over src/, apps/, fuzz/, tests/soak/ and the headers.
#   5. fuzz      libFuzzer targets of every parser of outside input (scripts/fuzz.sh).
#   6. soak      fuzzypid_soak for CI_SOAK_TICKS ticks (default 10,000,000, under a minute).
#   7. main      the README's main command, scripts/run-main.sh, as a fresh user runs it.
#   8. format    clang-format --dry-run -Werror over every C and C++ file git tracks (seconds).
# Any error, finding or sanitizer report fails the run. Environment:
#   CI_FUZZ_SECONDS  per fuzz target (default 25)
#   CI_SOAK_TICKS    soak length (default 10000000)
#   CI_STAGES        space-separated subset of the stage names (default: all)
set -euo pipefail
cd "$(dirname "$0")/.."
root="$(pwd)"
jobs="$(nproc)"
stages="${CI_STAGES:-format asan werror tidy cppcheck fuzz soak main}"

bash scripts/install-deps.sh

run_stage() {
  local name="$1"
  shift
  case " ${stages} " in *" ${name} "*) ;; *) return 0 ;; esac
  echo
  echo "==================================================================================="
  echo "== ci-checks: ${name}"
  echo "==================================================================================="
  local start=${SECONDS}
  "$@"
  echo "== ci-checks: ${name} passed in $((SECONDS - start)) s"
}

# -O1 -g1, as the ASan documentation suggests: reports keep function names and lines, and the
# sanitized tree compiles in 1,790 s of compiler time against 3,300 s at -O2 -g (UBSan's checks at
# -O2 were most of it; docs/robustness.md).
configure_asan() {
  cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" -DFUZZYPID_SANITIZE=ON \
    -DFUZZYPID_WERROR=ON -DFUZZYPID_BUILD_BENCH=OFF -DCMAKE_EXPORT_COMPILE_COMMANDS=ON >/dev/null
}

# Cases left to the Release suite of scripts/test.sh. Each takes 25-105 s under the sanitizers
# (about 700 s of the 1,080 s of test time the suite's cases took there, 2026-12-04) and repeats at
# scale code that shorter cases run under them too: the plant's step-convergence studies (every
# simulation case steps the plant), the tuner's determinism and search-box checks (TuneOnTheRobot,
# StagedTuning and tune.reports_its_evaluations_within_the_budget run the tuner), the long examples
# of docs/your_robot.md, the shipped controllers' documented figures, two package consumers (the
# others stay) and a compile-only check of exported headers. The fronts' CLI cases (a front run on
# held-out conditions, stopped and resumed, over two MPI ranks) repeat the front search that
# test_front runs under them; Open MPI's own allocations would also be reported as leaks. Doc blocks
# marked release-only (tests/docs/doc_snippets.py) are left out by their label: the front example
# of docs/tuning.md took 287 s there (35 s in Release) and runs the search test_front covers.
asan_release_only=(
  'robot\.JointPlant\.HighFrictionDefaultStepStaysWithinAMicroradianOfATenTimesFinerStep'
  'robot\.JointPlant\.CoupledDefaultStepStaysWithinAMicroradianWithoutArmatureAtFullSpeed'
  'ClosedLoopTest\.AtHighFrictionTheDefaultStepIsWithinAMicroradianOfATenTimesFinerStep'
  'sim_ab\.default_plant_step_converges_where_the_plant_is_stiff'
  'tune\.(warns_and_records_a_parameter_on_its_box|stages_same_seed_gives_the_same_file)'
  'tune\.(box_moves_with_the_training_tick|min_disk_margin_binds_and_is_recorded)'
  'tune\.same_seed_gives_the_same_file'
  'docs\.docs_your_robot_md_[0-9]+'
  'sim_ab\.(ur5|shipped)_controllers_match_their_documented_quality'
  'package\.find_package_controller(_file)?'
  'cli\.export_header\.namespaces_compile_or_are_refused'
  'tune\.front_(points|resume|mpi)'
)

stage_asan() {
  configure_asan
  cmake --build build-asan -j "${jobs}"
  local skip
  skip="^($(IFS='|' && echo "${asan_release_only[*]}"))\$"
  # detect_leaks: LeakSanitizer at exit; abort_on_error/halt_on_error: the first report fails the
  # test (the build already has -fno-sanitize-recover=all, halt_on_error covers any recoverable
  # check left). The allocation-counting tests replace operator new; ASan still intercepts the
  # malloc/free underneath, so they run unchanged.
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1 \
    UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
    ctest --test-dir build-asan --output-on-failure -j "${jobs}" --timeout 900 -E "${skip}" \
    -LE release-only
}

stage_werror() {
  echo "-Werror is on for every project target of the stage 'asan' build (FUZZYPID_WERROR=ON)."
  grep -q '^FUZZYPID_WERROR:BOOL=ON' build-asan/CMakeCache.txt
}

stage_tidy() {
  [ -f build-asan/compile_commands.json ] || configure_asan
  # GCC 12 compiles C++17 without an -std flag; clang-tidy 14 defaults to C++14, so pass it.
  # GoogleTest's TYPED_TEST_SUITE(Suite, Types) leaves its variadic part empty, which clang
  # -Wpedantic flags and GCC (the build compiler) accepts. GCC-only warning options of a target
  # (test_corpus in tests/rulefile) are unknown to clang.
  run-clang-tidy -p build-asan -j "${jobs}" -quiet -extra-arg=-std=c++17 \
    -extra-arg=-Wno-gnu-zero-variadic-macro-arguments -extra-arg=-Wno-unknown-warning-option \
    "${root}/(src|apps|tests)/.*\\.cpp\$" "${root}/build-asan/tests/headers/standalone/.*\\.cpp\$" \
    >build-asan/clang-tidy.log 2>&1 || {
    grep -E 'warning:|error:' build-asan/clang-tidy.log | sort -u
    echo "clang-tidy found issues (full log: build-asan/clang-tidy.log)" >&2
    return 1
  }
  echo "clang-tidy: clean ($(grep -c '^clang-tidy' build-asan/clang-tidy.log || true) files)"
}

stage_cppcheck() {
  # Third-party code (Eigen, KDL, urdfdom, GoogleTest) is not given to cppcheck; the reasons of
  # each suppression are in scripts/cppcheck-suppressions.txt. One configuration, the one the
  # build compiles (FUZZYPID_HAVE_ROBOT=1): given a -D, cppcheck checks only it instead of
  # guessing up to 12 per file (136 s instead of 237 s in CI), and no branch the build compiles
  # is left out.
  cppcheck --enable=warning,performance,portability --error-exitcode=1 --inline-suppr \
    --std=c++17 --language=c++ --quiet -j "${jobs}" -DFUZZYPID_HAVE_ROBOT=1 \
    --suppressions-list=scripts/cppcheck-suppressions.txt \
    -I include -I apps/common -I src/rulefile -I src/robot -I support \
    src apps fuzz tests/soak
  echo "cppcheck: clean"
}

stage_fuzz() {
  FUZZ_SECONDS="${CI_FUZZ_SECONDS:-25}" bash scripts/fuzz.sh
}

stage_soak() {
  local soak=build/bin/fuzzypid_soak
  if [ ! -x "${soak}" ]; then
    # The soak is a test (tests/soak/): it is configured with the tests.
    cmake -S . -B build-soak -G Ninja -DCMAKE_BUILD_TYPE=Release -DFUZZYPID_BUILD_TESTS=ON \
      -DFUZZYPID_BUILD_BENCH=OFF >/dev/null
    cmake --build build-soak -j "${jobs}" --target fuzzypid_soak
    soak=build-soak/bin/fuzzypid_soak
  fi
  "${soak}" --ticks "${CI_SOAK_TICKS:-10000000}" --seed 2
}

stage_main() {
  bash scripts/run-main.sh
  local f
  for f in out/ab/metrics.csv out/ab/trajectory.csv out/sweep-payload/sweep.csv; do
    [ -s "${f}" ] || { echo "scripts/run-main.sh did not write ${f}" >&2; return 1; }
  done
}

# Formatting that nothing checks drifts: every tracked C/C++ file must be as the checked-in
# .clang-format writes it (ReflowComments is off, so comments and code samples in them are kept).
stage_format() {
  local files
  mapfile -t files < <(git ls-files '*.cpp' '*.hpp' '*.h' '*.cpp.in' ':!:fuzz/corpus/**')
  clang-format --dry-run -Werror "${files[@]}"
  echo "clang-format: ${#files[@]} files as .clang-format writes them"
}

total_start=${SECONDS}
run_stage format stage_format
run_stage asan stage_asan
run_stage werror stage_werror
run_stage tidy stage_tidy
run_stage cppcheck stage_cppcheck
run_stage fuzz stage_fuzz
run_stage soak stage_soak
run_stage main stage_main
echo
echo "== ci-checks: all stages passed in $((SECONDS - total_start)) s"
