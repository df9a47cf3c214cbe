#include "fuzzypid/sim/experiment.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <utility>

#include "fuzzypid/control/joint_controller.hpp"
#include "fuzzypid/paper.hpp"
#include "fuzzypid/pid/pid.hpp"
#include "fuzzypid/robot/ik.hpp"
#include "fuzzypid/sim/nelder_mead.hpp"

namespace fuzzypid::sim {

namespace {

constexpr std::size_t kJoints = robot::kNumJoints;

// Gaussian samples by Box-Muller over mt19937_64, so the noise sequence is the same with every
// standard library (std::normal_distribution is implementation-defined).
class Gaussian {
 public:
  explicit Gaussian(std::uint64_t seed) : engine_(seed) {}
  double operator()(double sigma) {
    if (sigma == 0.0) return 0.0;
    constexpr double kTwoPi = 6.283185307179586;
    const double u1 = (static_cast<double>(engine_() >> 11) + 1.0) * 0x1.0p-53;
    const double u2 = static_cast<double>(engine_() >> 11) * 0x1.0p-53;
    return sigma * std::sqrt(-2.0 * std::log(u1)) * std::cos(kTwoPi * u2);
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace

const char* to_string(GainUnits g) noexcept {
  return g == GainUnits::Acceleration ? "acceleration" : "torque";
}
const char* to_string(PidForm f) noexcept {
  return f == PidForm::PerTick ? "per-tick" : "continuous";
}
const char* to_string(ControllerKind c) noexcept {
  switch (c) {
    case ControllerKind::Pid:
      return "pid";
    case ControllerKind::Fuzzy:
      return "fuzzy";
    case ControllerKind::PidTuned:
      return "pid-tuned";
  }
  return "unknown";
}

std::optional<Experiment> Experiment::create(const robot::RobotModel& model,
                                             const robot::CartesianPathSpec& path,
                                             const ExperimentOptions& options, std::string& error) {
  if (!(options.tick_s > 0.0) || !std::isfinite(options.initial_error_rad) ||
      !options.gains.finite()) {
    error = "invalid experiment options (tick must be > 0, gains and initial error finite)";
    return std::nullopt;
  }
  // The closed-form solver, seeded for the first sample with the paper's start joints so the
  // path takes the same (elbow-up, wrist-flipped) branch the paper's vector suggests.
  robot::JointPathResult planned =
      robot::plan_joint_path(model, path, robot::IkSolver::Analytic, robot::kPaperStartJoints);
  if (!planned.ok()) {
    error = "the path cannot be followed: " + planned.message;
    return std::nullopt;
  }
  const double planned_tick = planned.time_s.size() > 1 ? planned.time_s[1] - planned.time_s[0] : 0;
  if (std::fabs(planned_tick - options.tick_s) > 1e-12) {
    error = "the path's sample interval (" + std::to_string(planned_tick) +
            " s) differs from the controller tick (" + std::to_string(options.tick_s) + " s)";
    return std::nullopt;
  }
  return Experiment(model, std::move(planned), options);
}

Experiment::Experiment(const robot::RobotModel& model, robot::JointPathResult path,
                       const ExperimentOptions& options)
    : model_(model),
      path_(std::move(path)),
      options_(options),
      supervisor_(paper::make_system<double>(options.conjunction, options.tables)) {
  const robot::JointVector links = model_.inertia_diagonal(path_.position_rad.front());
  for (std::size_t i = 0; i < kJoints; ++i)
    nominal_inertia_[i] = links[i] + options_.plant.armature_kgm2[i];
}

pid::Gains<double> Experiment::to_continuous(const pid::Gains<double>& g) const noexcept {
  if (options_.pid_form == PidForm::Continuous) return g;
  return {g.kp, g.ki / options_.tick_s, g.kd * options_.tick_s};
}

pid::Gains<double> Experiment::to_paper_units(const pid::Gains<double>& g) const noexcept {
  if (options_.pid_form == PidForm::Continuous) return g;
  return {g.kp, g.ki * options_.tick_s, g.kd / options_.tick_s};
}

robot::JointVector Experiment::torque_limit(const Scenario& scenario) const {
  robot::JointVector limit = model_.effort_limits_nm();
  if (scenario.accel_limit_rad_s2 > 0.0)
    for (std::size_t i = 0; i < kJoints; ++i)
      limit[i] = scenario.accel_limit_rad_s2 * nominal_inertia_[i];
  return limit;
}

robot::PlantConfig Experiment::plant_config(const Scenario& scenario) const {
  robot::PlantConfig config = options_.plant;
  config.inertia_scale.fill(scenario.inertia_scale);
  for (std::size_t i = 0; i < kJoints; ++i)
    config.damping_nms[i] = scenario.damping_per_s * nominal_inertia_[i];
  config.torque_limit_nm = torque_limit(scenario);
  return config;
}

robot::JointVector Experiment::initial_position() const {
  robot::JointVector q0 = path_.position_rad.front();
  for (double& q : q0)
    q -= options_.initial_error_rad;
  return q0;
}

std::array<pid::Config<double>, kJoints> Experiment::pid_configs(
    const robot::JointVector& limit, const pid::Gains<double>& paper_gains) const {
  // The controller knows the actuator limit (in its own units), so conditional integration stops
  // windup when the plant saturates.
  const bool acceleration = options_.gain_units == GainUnits::Acceleration;
  std::array<pid::Config<double>, kJoints> configs{};
  for (std::size_t i = 0; i < kJoints; ++i) {
    pid::Config<double>& c = configs[i];
    c.gains = to_continuous(paper_gains);
    c.derivative_source = options_.derivative;
    c.derivative_on = pid::DerivativeOn::Error;
    c.anti_windup = pid::AntiWindup::Clamping;
    const double u_max = acceleration ? limit[i] / nominal_inertia_[i] : limit[i];
    c.output_min = -u_max;
    c.output_max = u_max;
  }
  return configs;
}

std::array<pid::Pid<double>, kJoints> Experiment::make_pid(
    const robot::JointVector& limit, const std::optional<pid::Gains<double>>& gains) const {
  const auto configs = pid_configs(limit, gains.value_or(options_.gains));
  std::array<pid::Pid<double>, kJoints> joints;
  for (std::size_t i = 0; i < kJoints; ++i)
    joints[i] = pid::Pid<double>(configs[i]);
  return joints;
}

std::array<paper::FuzzyPid<double>, kJoints> Experiment::make_fuzzy_pid(
    const robot::JointVector& limit, const std::optional<pid::Gains<double>>& gains) const {
  const auto configs = pid_configs(limit, gains.value_or(options_.gains));
  // dK is in the paper's units: convert it like the gains themselves.
  const pid::Gains<double> unit = to_continuous({1.0, 1.0, 1.0});
  std::array<paper::FuzzyPid<double>, kJoints> joints;
  for (std::size_t i = 0; i < kJoints; ++i) {
    control::FuzzyPidConfig<double> fc;
    fc.pid = configs[i];
    fc.error_scale = options_.error_scale;
    fc.error_rate_scale = options_.error_rate_scale;
    fc.gain_update = options_.gain_update;
    fc.output_scale = {options_.output_scale[0] * unit.kp, options_.output_scale[1] * unit.ki,
                       options_.output_scale[2] * unit.kd};
    joints[i] = paper::FuzzyPid<double>(&supervisor_, fc);
  }
  return joints;
}

robot::JointVector Experiment::torque_from_command(const robot::JointVector& u) const noexcept {
  if (options_.gain_units != GainUnits::Acceleration) return u;
  robot::JointVector torque{};
  for (std::size_t i = 0; i < kJoints; ++i)
    torque[i] = nominal_inertia_[i] * u[i];
  return torque;
}

RunResult Experiment::run(const Scenario& scenario, ControllerKind kind,
                          const std::optional<pid::Gains<double>>& gains) const {
  RunResult result;
  const ExperimentOptions& o = options_;
  robot::JointPlant plant(model_, plant_config(scenario));
  if (!plant.valid()) {
    result.error = "invalid plant configuration for scenario " + scenario.name;
    return result;
  }
  const robot::JointVector limit = torque_limit(scenario);
  plant.reset(initial_position(), robot::JointVector{});

  Gaussian noise(o.noise_seed);
  const std::size_t ticks = path_.time_s.size();
  result.rows.reserve(ticks * kJoints);

  auto simulate = [&](auto& controller) -> bool {
    for (std::size_t k = 0; k < ticks; ++k) {
      const double t = path_.time_s[k];
      const robot::JointVector& qd_ref = path_.position_rad[k];
      const robot::JointVector& vd_ref = path_.velocity_rad_s[k];
      robot::JointVector q_meas = plant.position();
      robot::JointVector v_meas = plant.velocity();
      for (std::size_t i = 0; i < kJoints; ++i) {
        q_meas[i] += noise(scenario.position_noise_rad);
        v_meas[i] += noise(scenario.velocity_noise_rad_s);
      }
      control::JointInput<double, kJoints> in;
      in.desired_position_rad = qd_ref;
      in.desired_velocity_rad_s = vd_ref;
      in.measured_position_rad = q_meas;
      in.measured_velocity_rad_s = v_meas;
      const auto command = controller.step(in, o.tick_s);
      if (is_fault(command.status)) ++result.controller_faults;
      const robot::JointVector torque = torque_from_command(command.torque_nm);
      robot::JointVector disturbance{};
      for (std::size_t i = 0; i < kJoints; ++i) {
        TrajectoryRow row;
        row.t_s = t;
        row.joint = static_cast<int>(i) + 1;
        row.theta_d = qd_ref[i];
        row.theta = plant.position()[i];
        row.error = qd_ref[i] - plant.position()[i];
        row.error_rate = vd_ref[i] - plant.velocity()[i];
        row.u = command.torque_nm[i];
        const pid::Gains<double> g = to_paper_units(controller.joint(i).gains());
        row.kp = g.kp;
        row.ki = g.ki;
        row.kd = g.kd;
        result.rows.push_back(row);
        disturbance[i] = scenario.pulses.at(t) * nominal_inertia_[i];
      }
      if (k + 1 == ticks) break;
      const robot::PlantStatus s = plant.step(torque, path_.time_s[k + 1] - t, disturbance);
      if (s == robot::PlantStatus::Saturated) ++result.saturated_ticks;
      if (s == robot::PlantStatus::InvalidInput || s == robot::PlantStatus::NumericalError) {
        result.error = std::string("plant step failed at t = ") + std::to_string(t) +
                       " s: " + robot::to_string(s);
        return false;
      }
    }
    return true;
  };

  if (kind == ControllerKind::Fuzzy) {
    control::JointController<double, kJoints, paper::FuzzyPid<double>> controller(
        make_fuzzy_pid(limit, gains));
    result.ok = simulate(controller);
  } else {
    control::JointController<double, kJoints, pid::Pid<double>> controller(make_pid(limit, gains));
    result.ok = simulate(controller);
  }
  return result;
}

double total_itae(const std::vector<TrajectoryRow>& rows, double tick_s) {
  double sum = 0.0;
  for (const TrajectoryRow& r : rows)
    sum += r.t_s * std::fabs(r.error) * tick_s;
  return sum;
}

TuningResult tune_pid(const Experiment& experiment, const Scenario& scenario) {
  const pid::Gains<double> g0 = experiment.options().gains;
  const auto to_gains = [](const std::array<double, 3>& x) {
    return pid::Gains<double>{std::pow(10.0, x[0]), std::pow(10.0, x[1]), std::pow(10.0, x[2])};
  };
  const auto objective = [&](const std::array<double, 3>& x) {
    const RunResult r = experiment.run(scenario, ControllerKind::PidTuned, to_gains(x));
    if (!r.ok || r.controller_faults != 0) return std::numeric_limits<double>::infinity();
    const double itae = total_itae(r.rows, experiment.options().tick_s);
    return std::isfinite(itae) ? itae : std::numeric_limits<double>::infinity();
  };
  // Search in decades, from the paper's gains, half a decade per initial step.
  const std::array<double, 3> start = {std::log10(g0.kp), std::log10(std::max(g0.ki, 1e-9)),
                                       std::log10(g0.kd)};
  const auto best = nelder_mead<3>(objective, start, {0.5, 0.5, 0.5}, 1e-9, 300);
  return {to_gains(best.x), best.value, best.evaluations};
}

}  // namespace fuzzypid::sim
