#include "fuzzypid/controller/joint_controllers.hpp"

namespace fuzzypid::controller {

namespace {

pid::Gains<double> scaled(const pid::Gains<double>& g, const pid::Gains<double>& f) noexcept {
  return {g.kp * f.kp, g.ki * f.ki, g.kd * f.kd};
}

}  // namespace

pid::Gains<double> bandwidth_factors(const ControllerSpec& spec, std::size_t joint) {
  const double s = joint < spec.bandwidth_scale.size() ? spec.bandwidth_scale[joint] : 1.0;
  return {s * s, s * s * s, s};
}

pid::Config<double> pid_config(const ControllerSpec& spec, std::size_t joint, double output_limit) {
  const pid::Gains<double> f = bandwidth_factors(spec, joint);
  pid::Config<double> c;
  c.gains = scaled(to_continuous(spec.gains, spec.units.form, spec.units.tick_s), f);
  c.derivative_source = spec.pid.derivative;
  c.derivative_on = spec.pid.derivative_on;
  c.anti_windup = spec.pid.anti_windup;
  c.derivative_filter_s = spec.pid.derivative_filter_s / f.kd;
  c.observer_bandwidth_hz = spec.pid.observer_bandwidth_hz;
  c.observer_delay_ticks = spec.pid.observer_delay_ticks;
  // The controller knows the actuator limit (in its own units), so conditional integration stops
  // windup when the plant saturates.
  c.output_min = -output_limit;
  c.output_max = output_limit;
  return c;
}

supervisor::FuzzyPidConfig<double> fuzzy_pid_config(const ControllerSpec& spec, std::size_t joint,
                                                    double output_limit) {
  const PidForm form = spec.units.form;
  const double dt = spec.units.tick_s;
  const pid::Gains<double> f = bandwidth_factors(spec, joint);
  supervisor::FuzzyPidConfig<double> fc;
  fc.pid = pid_config(spec, joint, output_limit);
  fc.error_scale = spec.supervisor.error_scale;
  fc.error_rate_scale = spec.supervisor.error_rate_scale;
  fc.gain_min = scaled(to_continuous(spec.gain_min, form, dt), f);
  fc.gain_max = scaled(to_continuous(spec.gain_max, form, dt), f);
  (void)with_family(
      spec.family,
      [&](auto family) {
        decltype(family)::configure(spec, fc);
        return true;
      },
      false);
  // configure() sets the output scales in gain units from the scaled K0 (ratio families) or from
  // the file's scales (fuzzy: converted like the gains, unscaled): the latter get the joint's
  // factors here, so that every gain the supervisor produces carries them.
  if (family_traits(spec.family).output_scale == OutputScale::Scales) {
    fc.output_scale = {fc.output_scale[0] * f.kp, fc.output_scale[1] * f.ki,
                       fc.output_scale[2] * f.kd};
  }
  return fc;
}

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
  JointConfigs configs;
  for (std::size_t i = 0; i < kJoints; ++i)
    configs[i] = fuzzy_pid_config(spec, i, output_limit[i]);
  return build(spec, configs, error);
}

std::optional<JointControllers> JointControllers::create(const ControllerSpec& spec,
                                                         const JointConfigs& configs,
                                                         std::string& error) {
  if (std::string bad = validate(spec); !bad.empty()) {
    error = std::move(bad);
    return std::nullopt;
  }
  return build(spec, configs, error);
}

std::optional<JointControllers> JointControllers::build(const ControllerSpec& spec,
                                                        const JointConfigs& configs,
                                                        std::string& error) {
  FamilyTable::Runtime joints;
  const bool built = with_family(
      spec.family,
      [&](auto family) { return decltype(family)::build(spec, configs, joints, error); }, false);
  if (!built) {
    if (error.empty()) error = "unknown controller family";
    return std::nullopt;
  }
  return JointControllers(spec, std::move(joints));
}

}  // namespace fuzzypid::controller
