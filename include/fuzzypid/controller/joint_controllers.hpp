// The six joints' controller described by a controller file, ready to run: a fixed PID, a
// gain-scheduled PID or a fuzzy PID per joint, in continuous-time SI form (per-tick gains are
// converted once, by controller::to_continuous). Built at set-up (may allocate); step() runs
// allocation-free and never throws.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <variant>

#include "fuzzypid/controller/controller_spec.hpp"
#include "fuzzypid/controller/families.hpp"
#include "fuzzypid/controller/runtime.hpp"
#include "fuzzypid/pid/pid.hpp"
#include "fuzzypid/supervisor/fuzzy_pid.hpp"

namespace fuzzypid::controller {

// The inner PID configuration of joint `joint` (0 .. 5) in every family: gains in continuous
// form with the joint's bandwidth scale applied (ControllerSpec::bandwidth_scale), output limited
// to +/- output_limit, in the controller's units.
[[nodiscard]] pid::Config<double> pid_config(const ControllerSpec& spec, std::size_t joint,
                                             double output_limit);
// The fuzzy PID configuration of joint `joint` of a supervised family (its configure() sets what
// output_scale means; K0, the output scales in gain units and the bounds carry the joint's
// bandwidth scale).
[[nodiscard]] supervisor::FuzzyPidConfig<double> fuzzy_pid_config(const ControllerSpec& spec,
                                                                  std::size_t joint,
                                                                  double output_limit);
// The factors joint `joint`'s bandwidth scale s puts on (kp, ki, kd): s², s³, s (joints 0 .. 5;
// any other joint has none: 1, 1, 1).
[[nodiscard]] pid::Gains<double> bandwidth_factors(const ControllerSpec& spec, std::size_t joint);

// Owns the supervisor its fuzzy or scheduled joints point to: movable, not copyable.
class JointControllers {
 public:
  // output_limit[i]: |u_i| <= output_limit[i] in the controller's units (rad/s² with acceleration
  // units; +inf for none). Returns nullopt with `error` set for an invalid spec.
  [[nodiscard]] static std::optional<JointControllers> create(const ControllerSpec& spec,
                                                              const Vector& output_limit,
                                                              std::string& error);
  // The spec's family and supervisor (tables, rule file or schedule) with one configuration per
  // joint in place of the ones the spec gives, for what a file cannot say: e.g. a gain update or
  // an integral limit that differs between joints. Start from fuzzy_pid_config(spec, i, limit_i);
  // the pid family uses configs[i].pid only. spec() is then where the joints started from, not
  // their numbers. Returns nullopt with `error` set for an invalid spec or configuration.
  [[nodiscard]] static std::optional<JointControllers> create(const ControllerSpec& spec,
                                                              const JointConfigs& configs,
                                                              std::string& error);

  // One tick of all joints (see supervisor::JointController::step); the outputs (`output`) are
  // in the controller's units (rad/s² with acceleration units).
  [[nodiscard]] Command step(const Input& in, double dt_s) noexcept {
    return visit_joints(joints_, [&](auto& joints) noexcept { return joints.step(in, dt_s); });
  }

  // The gains joint i used in its last step, in continuous SI form.
  pid::Gains<double> gains(std::size_t i) const noexcept {
    return visit_joints(joints_, [i](const auto& joints) noexcept { return joints.gains(i); });
  }
  // The same in the file's units (per-tick when the file's form is per-tick).
  pid::Gains<double> file_gains(std::size_t i) const noexcept {
    return from_continuous(gains(i), spec_.units.form, spec_.units.tick_s);
  }
  // The inner PID of joint i (its integral, output and saturation after the last step).
  const pid::Pid<double>& pid(std::size_t i) const noexcept {
    return visit_joints(joints_, [i](const auto& joints) noexcept -> const pid::Pid<double>& {
      return joints.pid(i);
    });
  }

  const ControllerSpec& spec() const noexcept { return spec_; }

 private:
  JointControllers(const ControllerSpec& spec, FamilyTable::Runtime joints)
      : spec_(spec), joints_(std::move(joints)) {}

  // The joints of a validated spec with these configurations.
  static std::optional<JointControllers> build(const ControllerSpec& spec,
                                               const JointConfigs& configs, std::string& error);

  ControllerSpec spec_;
  // One alternative per runtime of the families in families.hpp's list.
  FamilyTable::Runtime joints_;
};

}  // namespace fuzzypid::controller
