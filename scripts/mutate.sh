#!/usr/bin/env bash
# A small mutation pass: each mutant is a one-line bug put into the library (or a tool) with sed;
# the tests that guard that line are rebuilt and run; the mutant is "killed" when a build or a
# test fails, "survived" otherwise; the file is then restored with git checkout. Prints one line
# per mutant and the mutation score. Not run in CI (minutes per mutant on a small machine).
#
# Usage: scripts/mutate.sh [ID...]        (default: every mutant below)
#   BUILD_DIR=build   an already configured build tree (Ninja)
#   TESTS_FROM=REV    run the mutants against the tests (tests/) of revision REV instead of the
#                     working tree's -- e.g. the score before a change to the tests; tests/ is
#                     restored afterwards
# Refuses to start when a mutated file has uncommitted changes (they would be lost by the revert).
set -uo pipefail
cd "$(dirname "$0")/.."
build="${BUILD_DIR:-build}"
[ -f "${build}/build.ninja" ] || { echo "mutate.sh: configure ${build} first (Ninja)" >&2; exit 2; }

# ID | file | sed expression (applied with sed -i -e) | what guards it: bin:TARGET (a test binary,
# built and run), build:TARGET (built only), ctest:REGEX (ctest cases run). The first six are the
# survivors of the issue-20 audit; the coupled plant's RK4 weight is left to its owner.
mutants=(
  "triangle_open_right|include/fuzzypid/fuzzy/membership.hpp|s/return c == detail::infinity<Scalar>() ? h \* Scalar(1)/return c == detail::infinity<Scalar>() ? h * Scalar(0)/|bin:test_membership"
  "d_on_measurement_uses_setpoint_rate|include/fuzzypid/pid/pid.hpp|s/d_raw = in.setpoint_rate \* Scalar(0) - in.measurement_rate;/d_raw = in.setpoint_rate - in.measurement_rate;/|bin:test_pid"
  "reader_drops_derivative_on|src/controller_file/controller_file.cpp|s/s.pid.derivative_on = p->choice(\"derivative_on\"/(void)p->choice(\"derivative_on\"/|bin:test_controller_file"
  "pid_config_drops_derivative_on|src/controller/joint_controllers.cpp|/c.derivative_on = spec.pid.derivative_on;/d|bin:test_controller_file bin:test_joint_controller"
  "incremental_gain_update_ignored|include/fuzzypid/controller/families/fuzzy.hpp|s/config.gain_update = spec.supervisor.gain_update;/config.gain_update = supervisor::GainUpdate::Absolute;/|bin:test_controller_file bin:test_joint_controller"
  "family_dispatch_always_first|include/fuzzypid/controller/families.hpp|s/(family.index() == I ?/(I == 0 ?/|bin:test_sixth_family bin:test_controller_file"
  "runner_worker_takes_rank0_block|src/tune/runner.cpp|s/block_begin(jobs, transport_->rank, transport_->size),/block_begin(jobs, transport_->rank - 1, transport_->size),/|bin:test_front"
  "tuner_swaps_output_scales|src/tune/parameters.cpp|s/s.supervisor.output_scale = {p(5), p(6), p(7)};/s.supervisor.output_scale = {p(5), p(7), p(6)};/|bin:test_tune bin:test_parameters"
  "mc_friction_from_payload_draw|src/sim/condition_set.cpp|s/(friction.second - friction.first) \* u_friction;/(friction.second - friction.first) * u_payload;/|bin:test_condition_set"
  # Our own: the core.
  "triangle_left_edge_slope|include/fuzzypid/fuzzy/membership.hpp|s/h \* (x - a) \/ (b - a);/h * (x - a) \/ (c - a);/|bin:test_membership"
  "trapezoid_right_edge_slope|include/fuzzypid/fuzzy/membership.hpp|s/h \* (d - x) \/ (d - c);/h * (d - x) \/ (d - b);/|bin:test_membership"
  "integral_ignores_dt|include/fuzzypid/pid/pid.hpp|s/const Scalar increment = g.ki \* e \* dt_s;/const Scalar increment = g.ki * e;/|bin:test_pid"
  "clamping_upper_side_drops_increment_check|include/fuzzypid/pid/pid.hpp|s/if (trial > hi \&\& increment > Scalar(0))/if (trial > hi)/|bin:test_pid"
  "back_calculation_sign|include/fuzzypid/pid/pid.hpp|s/config_.tracking_gain_per_s \* (u - v) \* dt_s/config_.tracking_gain_per_s * (v - u) * dt_s/|bin:test_pid"
  "incremental_uses_pid_gains|include/fuzzypid/supervisor/fuzzy_pid.hpp|s/gain_update_ == GainUpdate::Absolute ? pid_.gains() : gains_/gain_update_ == GainUpdate::Absolute ? gains_ : pid_.gains()/|bin:test_fuzzy_pid"
  "file_numbers_15_digits|src/controller/controller_spec.cpp|s/\"%.17g\", v);/\"%.15g\", v);/|bin:test_controller_file"
  # Our own: issue 20's output writer, export-header and rt_loop.
  "writer_accepts_special_files|apps/common/output_paths.cpp|s/  if (!S_ISREG(st.st_mode))$/  if (false)/|bin:cli_common_tests build:fuzzypid_cli build:rt_loop build:sim_ab ctest:^cli\.outputs\."
  "writer_ignores_inputs|apps/common/output_paths.cpp|s/in.st_dev == st.st_dev \&\& in.st_ino == st.st_ino/false/|bin:cli_common_tests build:fuzzypid_cli build:rt_loop build:sim_ab ctest:^cli\.outputs\."
  "writer_ignores_flush_errors|apps/common/output_file.cpp|s/bool ok = std::fflush(file_) == 0 \&\& std::ferror(file_) == 0;/bool ok = true;/|bin:cli_common_tests build:fuzzypid_cli ctest:^cli\.outputs\."
  "namespace_allows_std|src/codegen/export_header.cpp|s/\"module\", \"std\", \"posix\"/\"module\", \"std_\", \"posix\"/|build:fuzzypid_cli ctest:^cli\.export_header\."
  "float_range_unchecked|src/codegen/export_header.cpp|s/std::fabs(v) > static_cast<double>(FLT_MAX)/std::fabs(v) > 1e300/|build:fuzzypid_cli ctest:^cli\.export_header\."
  "rt_loop_ignores_sigterm|apps/rt_loop/main.cpp|s/for (int sig : {SIGINT, SIGTERM, SIGHUP})/for (int sig : {SIGINT})/|build:rt_loop ctest:^rt_loop\.exit_codes"
  # Our own: export-rules (the fuzzy controller beside the exported rule file, the surface).
  "fuzzy_from_rule_table_drops_pid_options|src/controller/controller_spec.cpp|s/  s.pid = rules.pid;/  s.pid = {};/|bin:test_controller_file build:fuzzypid_cli build:sim_ab ctest:^cli\.export_rules\."
  "surface_swaps_the_scales|apps/fuzzypid/export_rules.cpp|s/x \/ spec.supervisor.error_scale, y \/ spec.supervisor.error_rate_scale/x \/ spec.supervisor.error_rate_scale, y \/ spec.supervisor.error_scale/|build:fuzzypid_cli build:fuzzylite_surface ctest:^cli\.export_rules\."
  # Issue 28's survivors, each now killed by a test of its own part.
  "rule_base_drops_lock_previous|src/codegen/export_rule_base.cpp|/h += v + \".lock_previous = \" + b(out.lock_previous)/d|bin:test_export_header"
  "rule_check_ignores_antecedent_hedges|src/rulefile/rule_check.cpp|s/key.items.emplace_back(static_cast<int>(t.kind), t.input, t.term, hedges);/key.items.emplace_back(static_cast<int>(t.kind), t.input, t.term, std::vector<int>{});/|bin:test_rule_check"
  "tsukamoto_takes_integral_defuzzifier|src/rulefile/fis_reader.cpp|s/type_ == \"tsukamoto\") \&\& !weighted/type_ == \"none\") \&\& !weighted/|bin:test_rule_file_constructs bin:test_rule_file"
  "lost_stderr_ignored|apps/common/cli.hpp|s/return code == kExitOk \&\& std::ferror(stderr) != 0 ? kExitFailure : code;/return code;/|build:fuzzypid_cli build:rt_loop ctest:^(cli\.check_rules\.|rt_loop\.exit_codes)"
  "validation_experiments_shifted|src/tune/tune.cpp|s/s.validation_ex.assign(ex.begin() + static_cast<std::ptrdiff_t>(n), ex.end());/s.validation_ex.assign(ex.begin() + static_cast<std::ptrdiff_t>(n) - 1, ex.end() - 1);/|bin:test_tune"
  "monotone_ratio_one_falls|src/tune/parameters.cpp|s/output_scale\[g\] >= 1.0 ? 1.0 : -1.0;/output_scale[g] > 1.0 ? 1.0 : -1.0;/|bin:test_parameters"
  "hermite_slope_weights_swapped|src/robot/path_file.cpp|s/return (h1 \* s0 + h0 \* s1) \/ (h0 + h1);/return (h0 * s0 + h1 * s1) \/ (h0 + h1);/|bin:robot_tests"
  "cartesian_rows_from_first_seed|src/robot/path_file.cpp|s/const JointVector\& from = k == 0 ? seed : q\[k - 1\];/const JointVector\& from = seed;/|bin:robot_tests"
  "gravity_feedforward_at_measured_angles|src/sim/closed_loop.cpp|s/feedforward_model_->gravity_torque(sample.theta_d);/feedforward_model_->gravity_torque(r.theta);/|bin:test_closed_loop"
  # Our own: issue 28's pass over the newest code (rule checks, the exported rule base, condition
  # files, the rule-table regulariser, the tuning record).
  "rule_check_ignores_conclusion_hedges|src/rulefile/rule_check.cpp|s/    return {c.term, hedges};/    return {c.term, {}};/|bin:test_rule_check"
  "rule_base_drops_rule_weight|src/codegen/export_rule_base.cpp|s/num(rule.block) + \", \" + lit(rule.weight)/num(rule.block) + \", \" + lit(1.0)/|bin:test_export_header"
  "rule_base_drops_input_enabled|src/codegen/export_rule_base.cpp|/h += v + \".enabled = \" + b(in.enabled)/d|bin:test_export_header"
  "scenario_drops_the_sets_gravity|src/sim/condition_set.cpp|s/^\\( *\\)PlantKeys plant) {$/\\1PlantKeys) { PlantKeys plant{};/|bin:test_condition_set"
  "mc_initial_error_from_friction_draw|src/sim/condition_set.cpp|s/(initial.second - initial.first) \* u_initial;/(initial.second - initial.first) * u_friction;/|bin:test_condition_set"
  "smoothness_drops_columns|src/tune/parameters.cpp|/if (j + 1 < kSets) sum += std::pow(std::log10(ratio\[g\]\[i\]\[j + 1\]) - v, 2);/d|bin:test_parameters"
  "stage_validation_cost_not_written|src/controller_file/controller_file.cpp|s/(std::isnan(st.validation_cost)/(true/|bin:test_controller_file"
  "regulariser_writes_smoothness_as_monotone|src/controller_file/controller_file.cpp|s/\"monotone = \" + format_double(g.monotone)/\"monotone = \" + format_double(g.smoothness)/|bin:test_controller_file"
  # Our own: issue 29's drive metrics and faults.
  "reversals_forget_the_last_significant_change|src/sim/metrics.cpp|s/    if (!(std::fabs(d) > h)) continue;/    if (!(std::fabs(d) > h)) { last = 0; continue; }/|bin:test_sim_metrics"
  "overshoot_on_a_contour_relative_to_the_start_error|src/sim/metrics.cpp|s/closed ? std::max(excursion, travel) : travel;/travel;/|bin:test_sim_metrics"
  "upper_joint_limits_unchecked|src/sim/faults.cpp|s/theta\[i\] > upper_rad_\[i\]/false/|bin:test_sim_metrics bin:test_run_outputs"
  "saturation_only_when_the_plant_clamps|src/sim/experiment.cpp|s/ applied >= (1.0 - 1e-9) \* torque_limit_nm\[i\];/ false;/|bin:test_run_outputs"
  "faults_never_fail_a_run|apps/sim_ab/main.cpp|s/  if (faulted == 0) return 0;/  if (faulted >= 0) return 0;/|build:sim_ab build:rt_loop ctest:^sim_ab\.faults_are_counted"
)

restore_tests() {
  if [ -n "${TESTS_FROM:-}" ]; then git checkout HEAD -- tests; fi
}
current=""
revert() {
  if [ -n "${current}" ]; then git checkout -- "${current}"; fi
  current=""
}
trap 'revert; restore_tests' EXIT
trap 'exit 130' INT TERM

selected=("$@")
wanted() {
  [ ${#selected[@]} -eq 0 ] && return 0
  local s
  for s in "${selected[@]}"; do [ "$s" = "$1" ] && return 0; done
  return 1
}

for m in "${mutants[@]}"; do
  IFS='|' read -r id file expr guards <<<"${m}"
  wanted "${id}" || continue
  if ! git diff --quiet -- "${file}"; then
    echo "mutate.sh: ${file} has uncommitted changes; commit or stash them first" >&2
    exit 2
  fi
done
if [ -n "${TESTS_FROM:-}" ]; then
  git diff --quiet -- tests || { echo "mutate.sh: tests/ has uncommitted changes" >&2; exit 2; }
  git checkout "${TESTS_FROM}" -- tests || exit 2
fi

killed=0
total=0
survivors=()
for m in "${mutants[@]}"; do
  IFS='|' read -r id file expr guards <<<"${m}"
  wanted "${id}" || continue
  current="${file}"
  sed -i -e "${expr}" "${file}"
  if git diff --quiet -- "${file}"; then
    echo "mutate.sh: ${id}: the expression no longer matches ${file}" >&2
    revert
    exit 2
  fi
  total=$((total + 1))
  targets=()
  bins=()
  regex=""
  for g in ${guards}; do
    case "${g}" in
      bin:*) targets+=("${g#bin:}"); bins+=("${g#bin:}") ;;
      build:*) targets+=("${g#build:}") ;;
      ctest:*) regex="${g#ctest:}" ;;
    esac
  done
  verdict="survived"
  if ! ninja -C "${build}" "${targets[@]}" >"${build}/mutate_${id}.log" 2>&1; then
    verdict="killed (build)"
  else
    for b in "${bins[@]}"; do
      if ! "${build}/bin/${b}" >>"${build}/mutate_${id}.log" 2>&1; then
        verdict="killed (${b})"
        break
      fi
    done
    if [ "${verdict}" = survived ] && [ -n "${regex}" ]; then
      if ! ctest --test-dir "${build}" -R "${regex}" >>"${build}/mutate_${id}.log" 2>&1; then
        verdict="killed (ctest ${regex})"
      fi
    fi
  fi
  revert
  if [ "${verdict}" = survived ]; then survivors+=("${id}"); else killed=$((killed + 1)); fi
  printf '%-44s %s\n' "${id}" "${verdict}"
done
# Rebuild what the mutants touched, from the restored sources.
restore_tests
echo "mutation score: ${killed}/${total} killed"
[ ${#survivors[@]} -eq 0 ] || echo "survivors: ${survivors[*]}"
