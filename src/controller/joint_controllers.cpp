#include "fuzzypid/controller/joint_controllers.hpp"

namespace fuzzypid::controller {

pid::Config<double> pid_config(const ControllerSpec& spec, double output_limit) {
  pid::Config<double> c;
  c.gains = to_continuous(spec.gains, spec.units.form, spec.units.tick_s);
  c.derivative_source = spec.pid.derivative;
  c.derivative_on = spec.pid.derivative_on;
  c.anti_windup = spec.pid.anti_windup;
  c.derivative_filter_s = spec.pid.derivative_filter_s;
  // The controller knows the actuator limit (in its own units), so conditional integration stops
  // windup when the plant saturates.
  c.output_min = -output_limit;
  c.output_max = output_limit;
  return c;
}

control::FuzzyPidConfig<double> fuzzy_pid_config(const ControllerSpec& spec, double output_limit) {
  const PidForm form = spec.units.form;
  const double dt = spec.units.tick_s;
  control::FuzzyPidConfig<double> fc;
  fc.pid = pid_config(spec, output_limit);
  fc.error_scale = spec.supervisor.error_scale;
  fc.error_rate_scale = spec.supervisor.error_rate_scale;
  fc.gain_min = to_continuous(spec.gain_min, form, dt);
  fc.gain_max = to_continuous(spec.gain_max, form, dt);
  const auto& s = spec.supervisor.output_scale;
  if (spec.family == Family::Scheduled) {
    // K = K0 + K0 (R - 1) w: from K0 on the path to K0 R at large errors (gain_schedule.hpp).
    const pid::Gains<double>& k0 = fc.pid.gains;
    fc.output_scale = {k0.kp * (s[0] - 1.0), k0.ki * (s[1] - 1.0), k0.kd * (s[2] - 1.0)};
    fc.gain_update = control::GainUpdate::Absolute;
  } else if (spec.family == Family::FuzzyRules) {
    // K = K0 + K0 dK with dK = ratio - 1 (control/rule_table.hpp).
    const pid::Gains<double>& k0 = fc.pid.gains;
    fc.output_scale = {k0.kp, k0.ki, k0.kd};
    fc.gain_update = control::GainUpdate::Absolute;
  } else {
    // dK is in the file's units: convert it like the gains themselves.
    const pid::Gains<double> unit = to_continuous({1.0, 1.0, 1.0}, form, dt);
    fc.output_scale = {s[0] * unit.kp, s[1] * unit.ki, s[2] * unit.kd};
    fc.gain_update = spec.supervisor.gain_update;
  }
  return fc;
}

control::RuleTable<double> rule_table(const ControllerSpec& spec) {
  const RuleTableSpec& t = spec.supervisor.rule_table;
  control::RuleTable<double> r;
  r.schedule_ratio = spec.supervisor.output_scale;
  r.table = t.ratio;
  r.e_centers = t.error_centers;
  r.ec_centers = t.error_rate_centers;
  return r;
}

namespace {

// The six joints of a supervised family on `supervisor` (shared, not owned), joint i with
// configs[i]; nullopt with `error` set when a configuration is invalid. `what` names the family
// in that error.
template <class Supervisor>
std::optional<std::array<control::FuzzyPid<double, Supervisor>, kJoints>> supervised_joints(
    const Supervisor* supervisor,
    const std::array<control::FuzzyPidConfig<double>, kJoints>& configs, const char* what,
    std::string& error) {
  std::array<control::FuzzyPid<double, Supervisor>, kJoints> joints;
  for (std::size_t i = 0; i < kJoints; ++i) {
    if (!configs[i].valid()) {
      error = std::string("invalid ") + what + " configuration";
      return std::nullopt;
    }
    joints[i] = control::FuzzyPid<double, Supervisor>(supervisor, configs[i]);
  }
  return joints;
}

}  // namespace

std::optional<JointControllers> JointControllers::create(const ControllerSpec& spec,
                                                         const Vector& output_limit,
                                                         std::string& error) {
  if (std::string bad = validate(spec); !bad.empty()) {
    error = std::move(bad);
    return std::nullopt;
  }
  for (double l : output_limit) {
    if (!(l > 0.0)) {
      error = "output limits must be > 0";
      return std::nullopt;
    }
  }
  std::array<control::FuzzyPidConfig<double>, kJoints> configs;
  for (std::size_t i = 0; i < kJoints; ++i)
    configs[i] = fuzzy_pid_config(spec, output_limit[i]);
  return build(spec, configs, error);
}

std::optional<JointControllers> JointControllers::create(
    const ControllerSpec& spec, const std::array<control::FuzzyPidConfig<double>, kJoints>& configs,
    std::string& error) {
  if (std::string bad = validate(spec); !bad.empty()) {
    error = std::move(bad);
    return std::nullopt;
  }
  return build(spec, configs, error);
}

std::optional<JointControllers> JointControllers::build(
    const ControllerSpec& spec, const std::array<control::FuzzyPidConfig<double>, kJoints>& configs,
    std::string& error) {
  switch (spec.family) {
    case Family::Pid: {
      std::array<pid::Pid<double>, kJoints> joints;
      for (std::size_t i = 0; i < kJoints; ++i) {
        const pid::Config<double>& c = configs[i].pid;
        if (!c.valid()) {
          error = "invalid PID configuration";
          return std::nullopt;
        }
        joints[i] = pid::Pid<double>(c);
      }
      JointControllers out(spec, nullptr, nullptr);
      out.joints_ = PidJoints(joints);
      return out;
    }
    case Family::Fuzzy: {
      if (spec.supervisor.rule_model != nullptr) {
        // A rule file: the engine supervisor on the loaded model (both shared by the joints).
        auto engine = std::make_unique<const control::EngineSupervisor<double>>(
            spec.supervisor.rule_model.get());
        if (!engine->valid()) {
          error = "the rule file's model is not a valid supervisor (2 inputs, 3 outputs)";
          return std::nullopt;
        }
        auto joints = supervised_joints(engine.get(), configs, "fuzzy PID", error);
        if (!joints) return std::nullopt;
        JointControllers out(spec, nullptr, nullptr);
        out.rule_model_ = spec.supervisor.rule_model;
        out.engine_ = std::move(engine);
        out.joints_ = EngineJoints(*joints);
        return out;
      }
      auto tables = std::make_unique<const paper::System<double>>(
          paper::make_system<double>(spec.supervisor.conjunction, spec.supervisor.rule_base));
      auto joints = supervised_joints(tables.get(), configs, "fuzzy PID", error);
      if (!joints) return std::nullopt;
      JointControllers out(spec, std::move(tables), nullptr);
      out.joints_ = FuzzyJoints(*joints);
      return out;
    }
    case Family::FuzzyRules: {
      auto table = std::make_unique<const control::RuleTable<double>>(rule_table(spec));
      if (!table->valid()) {
        error = "invalid rule table (centers increasing and symmetric, ratios finite and > 0)";
        return std::nullopt;
      }
      auto joints = supervised_joints(table.get(), configs, "fuzzy-rules PID", error);
      if (!joints) return std::nullopt;
      JointControllers out(spec, nullptr, nullptr);
      out.rule_table_ = std::move(table);
      out.joints_ = RuleTableJoints(*joints);
      return out;
    }
    case Family::Scheduled: {
      auto schedule = std::make_unique<const control::GainSchedule<double>>();
      auto joints = supervised_joints(schedule.get(), configs, "scheduled PID", error);
      if (!joints) return std::nullopt;
      JointControllers out(spec, nullptr, std::move(schedule));
      out.joints_ = ScheduledJoints(*joints);
      return out;
    }
  }
  error = "unknown controller family";
  return std::nullopt;
}

}  // namespace fuzzypid::controller
