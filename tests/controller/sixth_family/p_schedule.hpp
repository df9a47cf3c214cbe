// The sixth family of this test build: "p-schedule", Kp = K0p (1 + (Rp - 1) w(Ke e, Kec ec)) with
// Ki, Kd fixed -- a proportional-only gain schedule. It is written as any family is
// (include/fuzzypid/controller/families/pid.hpp shows the shape) and, with its supervisor
// (proportional_ramp.hpp), is all that the build adds: controller files, the runtime, validation,
// header export and the tuner's parameter space take it from its traits and these functions.
#pragma once

#include <memory>
#include <string>

#include "fuzzypid/controller/controller_spec.hpp"
#include "fuzzypid/controller/family.hpp"
#include "fuzzypid/controller/runtime.hpp"
#include "proportional_ramp.hpp"

namespace fuzzypid_test {

struct PSchedule {
  static constexpr fuzzypid::controller::FamilyTraits kTraits{
      "p-schedule", "Kp = K0p (1 + (Rp - 1) min(1, Ke|e| + Kec|ec|)), Ki and Kd fixed",
      fuzzypid::controller::OutputScale::Ratios, false, false};
  using Runtimes = std::tuple<fuzzypid::controller::SupervisedJoints<ProportionalRamp<double>>>;

  // Ri and Rd have no effect here: a file that sets them is refused rather than ignored.
  [[nodiscard]] static std::string validate(const fuzzypid::controller::ControllerSpec& spec) {
    const auto& r = spec.supervisor.output_scale;
    if (r[1] != 1.0 || r[2] != 1.0)
      return "the p-schedule family schedules Kp only: output_scale must be [Rp, 1.0, 1.0]";
    return {};
  }

  static void configure(const fuzzypid::controller::ControllerSpec& spec,
                        fuzzypid::supervisor::FuzzyPidConfig<double>& config) noexcept {
    config.output_scale = {config.pid.gains.kp * (spec.supervisor.output_scale[0] - 1.0), 0.0, 0.0};
    config.gain_update = fuzzypid::supervisor::GainUpdate::Absolute;
  }

  template <class Code>
  [[nodiscard]] static fuzzypid::controller::SupervisorCode header_code(
      const fuzzypid::controller::ControllerSpec& /*spec*/, const Code& /*code*/) {
    return {"#include \"fuzzypid/supervisor/fuzzy_pid.hpp\"\n#include \"proportional_ramp.hpp\"\n",
            "template <class Scalar>\nusing Supervisor = fuzzypid_test::ProportionalRamp<Scalar>;"
            "\n\ntemplate <class Scalar>\ninline constexpr Supervisor<Scalar> kSupervisor{};\n\n"};
  }

  template <class Runtime>
  [[nodiscard]] static bool build(const fuzzypid::controller::ControllerSpec& /*spec*/,
                                  const fuzzypid::controller::JointConfigs& configs, Runtime& out,
                                  std::string& error) {
    using Joints = fuzzypid::controller::SupervisedJoints<ProportionalRamp<double>>;
    return fuzzypid::controller::make_supervised_joints(
        std::make_unique<const ProportionalRamp<double>>(), configs, "p-schedule PID",
        out.template emplace<Joints>(), error);
  }
};

}  // namespace fuzzypid_test
