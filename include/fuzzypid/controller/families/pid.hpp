// The pid family: a fixed PID per joint (Eq. 2), Kp, Ki, Kd.
#pragma once

#include <string>

#include "fuzzypid/controller/controller_spec.hpp"
#include "fuzzypid/controller/family.hpp"
#include "fuzzypid/controller/runtime.hpp"

namespace fuzzypid::controller::families {

struct Pid {
  static constexpr FamilyTraits kTraits{"pid", "a fixed PID: Kp, Ki, Kd", OutputScale::None, false,
                                        false};
  using Runtimes = std::tuple<FixedJoints>;

  // Checks beyond validate()'s, which the traits drive: none.
  [[nodiscard]] static std::string validate(const ControllerSpec& /*spec*/) { return {}; }
  // The supervisor's part of a joint's configuration: none.
  static void configure(const ControllerSpec& /*spec*/,
                        supervisor::FuzzyPidConfig<double>& /*config*/) noexcept {}

  // The header export of the supervisor (family.hpp, SupervisorCode). `code` writes what this
  // file cannot: code.literal(v), an exact literal of v as Scalar, and code.rule_base(model,
  // file), a rule file's model and its supervisor.
  template <class Code>
  [[nodiscard]] static SupervisorCode header_code(const ControllerSpec& /*spec*/,
                                                  const Code& /*code*/) {
    return {};
  }

  template <class Runtime>
  [[nodiscard]] static bool build(const ControllerSpec& /*spec*/, const JointConfigs& configs,
                                  Runtime& out, std::string& error) {
    return make_fixed_joints(configs, out.template emplace<FixedJoints>(), error);
  }
};

}  // namespace fuzzypid::controller::families
