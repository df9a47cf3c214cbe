// Compiled (not run) for a Cortex-M4F, float, -fno-exceptions -fno-rtti: a controller exported by
// `fuzzypid export-header` needs no parser, heap or OS on the target, one with a rule file
// (engine_tip_fuzzy: a Mamdani rule base as constexpr data), a tuned fuzzy-rules table and
// controllers with a bandwidth scale per joint (joint-indexed make_controller) included.
#include "engine_tip_fuzzy.hpp"
#include "per_joint_fuzzy.hpp"
#include "per_joint_pid.hpp"
#include "tuned_fuzzy.hpp"
#include "tuned_fuzzy_rules.hpp"
#include "tuned_scheduled.hpp"

namespace {
auto fuzzy = tuned_fuzzy::make_controller<float>(5.0f);
auto scheduled = tuned_scheduled::make_controller<float>(5.0f);
auto rules = tuned_fuzzy_rules::make_controller<float>(5.0f);
auto tipper = engine_tip_fuzzy::make_controller<float>(5.0f);
auto wrist_pid = per_joint_pid::make_controller<float>(3, 5.0f);
auto wrist_fuzzy = per_joint_fuzzy::make_controller<float>(3, 5.0f);
}  // namespace

extern "C" float exported_tick(float setpoint, float measurement) {
  fuzzypid::pid::Input<float> in;
  in.setpoint = setpoint;
  in.measurement = measurement;
  const bool ok = !fuzzypid::is_fault(fuzzy.update(in, 0.05f)) &&
                  !fuzzypid::is_fault(scheduled.update(in, 0.05f)) &&
                  !fuzzypid::is_fault(tipper.update(in, 0.05f)) &&
                  !fuzzypid::is_fault(rules.update(in, 0.05f)) &&
                  !fuzzypid::is_fault(wrist_pid.update(in, 0.05f)) &&
                  !fuzzypid::is_fault(wrist_fuzzy.update(in, 0.05f));
  return ok ? fuzzy.output() + scheduled.output() + tipper.output() + rules.output() +
                  wrist_pid.output() + wrist_fuzzy.output()
            : 0.0f;
}
