// The six joints' controller described by a controller file, ready to run: a fixed PID, a
// gain-scheduled PID or a fuzzy PID per joint, in continuous-time SI form (per-tick gains are
// converted once, by controller_file::to_continuous). Built at set-up (may allocate); step() runs
// allocation-free and never throws.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <variant>

#include "fuzzypid/control/fuzzy_pid.hpp"
#include "fuzzypid/control/gain_schedule.hpp"
#include "fuzzypid/control/joint_controller.hpp"
#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid/paper.hpp"
#include "fuzzypid/pid/pid.hpp"

namespace fuzzypid::controller_file {

inline constexpr std::size_t kJoints = 6;

using Vector = std::array<double, kJoints>;
using Command = control::JointCommand<double, kJoints>;
using PidJoints = control::JointController<double, kJoints, pid::Pid<double>>;
using FuzzyJoints =
    control::JointController<double, kJoints, control::FuzzyPid<double, paper::System<double>>>;
using ScheduledJoints =
    control::JointController<double, kJoints,
                             control::FuzzyPid<double, control::GainSchedule<double>>>;

// The inner PID configuration of every family (gains in continuous form, output limited to
// +/- output_limit, in the controller's units).
[[nodiscard]] pid::Config<double> pid_config(const ControllerSpec& spec, double output_limit);
// The fuzzy PID configuration of the fuzzy and scheduled families.
[[nodiscard]] control::FuzzyPidConfig<double> fuzzy_pid_config(const ControllerSpec& spec,
                                                               double output_limit);

class JointControllers {
 public:
  // output_limit[i]: |u_i| <= output_limit[i] in the controller's units (rad/s² with acceleration
  // units; +inf for none). Returns nullopt with `error` set for an invalid spec.
  [[nodiscard]] static std::optional<JointControllers> create(const ControllerSpec& spec,
                                                              const Vector& output_limit,
                                                              std::string& error);

  // One tick of all joints (see control::JointController::step).
  Command step(const Vector& desired_position, const Vector& desired_velocity,
               const Vector& measured_position, const Vector& measured_velocity,
               double dt_s) noexcept {
    if (auto* p = std::get_if<PidJoints>(&joints_))
      return p->step(desired_position, desired_velocity, measured_position, measured_velocity,
                     dt_s);
    if (auto* f = std::get_if<FuzzyJoints>(&joints_))
      return f->step(desired_position, desired_velocity, measured_position, measured_velocity,
                     dt_s);
    return std::get_if<ScheduledJoints>(&joints_)->step(desired_position, desired_velocity,
                                                        measured_position, measured_velocity, dt_s);
  }

  // The gains joint i used in its last step, in continuous SI form.
  pid::Gains<double> gains(std::size_t i) const noexcept {
    if (const auto* p = std::get_if<PidJoints>(&joints_)) return p->joint(i).gains();
    if (const auto* f = std::get_if<FuzzyJoints>(&joints_)) return f->joint(i).gains();
    return std::get_if<ScheduledJoints>(&joints_)->joint(i).gains();
  }
  // The same in the file's units (per-tick when the file's form is per-tick).
  pid::Gains<double> file_gains(std::size_t i) const noexcept {
    return from_continuous(gains(i), spec_.units.form, spec_.units.tick_s);
  }

  const ControllerSpec& spec() const noexcept { return spec_; }

 private:
  template <class Joints>
  JointControllers(const ControllerSpec& spec, Joints joints)
      : spec_(spec), joints_(std::move(joints)) {}

  ControllerSpec spec_;
  std::variant<PidJoints, FuzzyJoints, ScheduledJoints> joints_;
};

}  // namespace fuzzypid::controller_file
