// The six joints' controller described by a controller file, ready to run: a fixed PID, a
// gain-scheduled PID or a fuzzy PID per joint, in continuous-time SI form (per-tick gains are
// converted once, by controller::to_continuous). Built at set-up (may allocate); step() runs
// allocation-free and never throws.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <variant>

#include "fuzzypid/control/engine_supervisor.hpp"
#include "fuzzypid/control/fuzzy_pid.hpp"
#include "fuzzypid/control/gain_schedule.hpp"
#include "fuzzypid/control/joint_controller.hpp"
#include "fuzzypid/control/rule_table.hpp"
#include "fuzzypid/controller/controller_spec.hpp"
#include "fuzzypid/paper.hpp"
#include "fuzzypid/pid/pid.hpp"

namespace fuzzypid::controller {

inline constexpr std::size_t kJoints = 6;

using Vector = std::array<double, kJoints>;
using Input = control::JointInput<double, kJoints>;
using Command = control::JointOutput<double, kJoints>;
using PidJoints = control::JointController<double, kJoints, pid::Pid<double>>;
using FuzzyJoints =
    control::JointController<double, kJoints, control::FuzzyPid<double, paper::System<double>>>;
using EngineJoints =
    control::JointController<double, kJoints,
                             control::FuzzyPid<double, control::EngineSupervisor<double>>>;
using ScheduledJoints =
    control::JointController<double, kJoints,
                             control::FuzzyPid<double, control::GainSchedule<double>>>;
using RuleTableJoints =
    control::JointController<double, kJoints,
                             control::FuzzyPid<double, control::RuleTable<double>>>;

// The fuzzy-rules family's supervisor as the description gives it.
[[nodiscard]] control::RuleTable<double> rule_table(const ControllerSpec& spec);

// The inner PID configuration of every family (gains in continuous form, output limited to
// +/- output_limit, in the controller's units).
[[nodiscard]] pid::Config<double> pid_config(const ControllerSpec& spec, double output_limit);
// The fuzzy PID configuration of the fuzzy and scheduled families.
[[nodiscard]] control::FuzzyPidConfig<double> fuzzy_pid_config(const ControllerSpec& spec,
                                                               double output_limit);

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
  // an integral limit that differs between joints. Start from fuzzy_pid_config(spec, limit_i);
  // the pid family uses configs[i].pid only. spec() is then where the joints started from, not
  // their numbers. Returns nullopt with `error` set for an invalid spec or configuration.
  [[nodiscard]] static std::optional<JointControllers> create(
      const ControllerSpec& spec,
      const std::array<control::FuzzyPidConfig<double>, kJoints>& configs, std::string& error);

  // One tick of all joints (see control::JointController::step); the outputs (torque_nm) are
  // in the controller's units (rad/s² with acceleration units).
  [[nodiscard]] Command step(const Input& in, double dt_s) noexcept {
    if (auto* p = std::get_if<PidJoints>(&joints_)) return p->step(in, dt_s);
    if (auto* f = std::get_if<FuzzyJoints>(&joints_)) return f->step(in, dt_s);
    if (auto* r = std::get_if<EngineJoints>(&joints_)) return r->step(in, dt_s);
    if (auto* t = std::get_if<RuleTableJoints>(&joints_)) return t->step(in, dt_s);
    return std::get_if<ScheduledJoints>(&joints_)->step(in, dt_s);
  }

  // The gains joint i used in its last step, in continuous SI form.
  pid::Gains<double> gains(std::size_t i) const noexcept {
    if (const auto* p = std::get_if<PidJoints>(&joints_)) return p->joint(i).gains();
    if (const auto* f = std::get_if<FuzzyJoints>(&joints_)) return f->joint(i).gains();
    if (const auto* r = std::get_if<EngineJoints>(&joints_)) return r->joint(i).gains();
    if (const auto* t = std::get_if<RuleTableJoints>(&joints_)) return t->joint(i).gains();
    return std::get_if<ScheduledJoints>(&joints_)->joint(i).gains();
  }
  // The same in the file's units (per-tick when the file's form is per-tick).
  pid::Gains<double> file_gains(std::size_t i) const noexcept {
    return from_continuous(gains(i), spec_.units.form, spec_.units.tick_s);
  }
  // The inner PID of joint i (its integral, output and saturation after the last step).
  const pid::Pid<double>& pid(std::size_t i) const noexcept {
    if (const auto* p = std::get_if<PidJoints>(&joints_)) return p->joint(i);
    if (const auto* f = std::get_if<FuzzyJoints>(&joints_)) return f->joint(i).pid();
    if (const auto* r = std::get_if<EngineJoints>(&joints_)) return r->joint(i).pid();
    if (const auto* t = std::get_if<RuleTableJoints>(&joints_)) return t->joint(i).pid();
    return std::get_if<ScheduledJoints>(&joints_)->joint(i).pid();
  }

  const ControllerSpec& spec() const noexcept { return spec_; }

 private:
  // The joints of a validated spec with these configurations.
  static std::optional<JointControllers> build(
      const ControllerSpec& spec,
      const std::array<control::FuzzyPidConfig<double>, kJoints>& configs, std::string& error);

  JointControllers(const ControllerSpec& spec, std::unique_ptr<const paper::System<double>> tables,
                   std::unique_ptr<const control::GainSchedule<double>> schedule)
      : spec_(spec), tables_(std::move(tables)), schedule_(std::move(schedule)) {}

  ControllerSpec spec_;
  // The shared supervisors (on the heap: their addresses survive moves of this object).
  std::unique_ptr<const paper::System<double>> tables_;
  std::unique_ptr<const control::GainSchedule<double>> schedule_;
  std::shared_ptr<const fuzzy::EngineModel<double>> rule_model_;
  std::unique_ptr<const control::EngineSupervisor<double>> engine_;
  std::unique_ptr<const control::RuleTable<double>> rule_table_;
  std::variant<PidJoints, FuzzyJoints, ScheduledJoints, EngineJoints, RuleTableJoints> joints_;
};

}  // namespace fuzzypid::controller
