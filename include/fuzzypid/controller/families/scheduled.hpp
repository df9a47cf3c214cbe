// The scheduled family: K = K0 (1 + (R - 1) w(Ke e, Kec ec)), the eight-parameter gain schedule of
// supervisor/gain_schedule.hpp (K0, Ke, Kec, R).
#pragma once

#include <memory>
#include <string>

#include "fuzzypid/controller/controller_spec.hpp"
#include "fuzzypid/controller/family.hpp"
#include "fuzzypid/controller/runtime.hpp"
#include "fuzzypid/supervisor/gain_schedule.hpp"

namespace fuzzypid::controller::families {

struct Scheduled {
  static constexpr FamilyTraits kTraits{
      "scheduled",
      "K = K0 (1 + (R - 1) min(1, Ke|e| + Kec|ec|)): a gain schedule with eight parameters",
      OutputScale::Ratios, false, false};
  using Runtimes = std::tuple<SupervisedJoints<supervisor::GainSchedule<double>>>;

  [[nodiscard]] static std::string validate(const ControllerSpec& /*spec*/) { return {}; }

  // K = K0 + K0 (R - 1) w: from K0 on the path to K0 R at large errors (gain_schedule.hpp).
  static void configure(const ControllerSpec& spec,
                        supervisor::FuzzyPidConfig<double>& config) noexcept {
    const pid::Gains<double>& k0 = config.pid.gains;
    const auto& r = spec.supervisor.output_scale;
    config.output_scale = {k0.kp * (r[0] - 1.0), k0.ki * (r[1] - 1.0), k0.kd * (r[2] - 1.0)};
    config.gain_update = supervisor::GainUpdate::Absolute;
  }

  // The header export of the supervisor (family.hpp, SupervisorCode). `code` writes what this
  // file cannot: code.literal(v), an exact literal of v as Scalar, and code.rule_base(model,
  // file), a rule file's model and its supervisor.
  template <class Code>
  [[nodiscard]] static SupervisorCode header_code(const ControllerSpec& /*spec*/,
                                                  const Code& /*code*/) {
    return {
        "#include \"fuzzypid/supervisor/fuzzy_pid.hpp\"\n"
        "#include \"fuzzypid/supervisor/gain_schedule.hpp\"\n",
        "template <class Scalar>\nusing Supervisor = fuzzypid::supervisor::GainSchedule<Scalar>;"
        "\n\n// The shared, immutable supervisor the joints point to.\n"
        "template <class Scalar>\ninline constexpr Supervisor<Scalar> kSupervisor{};\n\n"};
  }

  template <class Runtime>
  [[nodiscard]] static bool build(const ControllerSpec& /*spec*/, const JointConfigs& configs,
                                  Runtime& out, std::string& error) {
    using Joints = SupervisedJoints<supervisor::GainSchedule<double>>;
    return make_supervised_joints(std::make_unique<const supervisor::GainSchedule<double>>(),
                                  configs, "scheduled PID", out.template emplace<Joints>(), error);
  }
};

}  // namespace fuzzypid::controller::families
