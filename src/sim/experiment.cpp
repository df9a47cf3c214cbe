#include "fuzzypid/sim/experiment.hpp"

#include <cmath>
#include <limits>
#include <utility>

#include "fuzzypid/controller_file/joint_controllers.hpp"
#include "fuzzypid/paper.hpp"
#include "fuzzypid/robot/ik.hpp"
#include "fuzzypid/sim/closed_loop.hpp"

namespace fuzzypid::sim {

namespace {

constexpr std::size_t kJoints = robot::kNumJoints;

}  // namespace

ControllerSpec default_controller(const ExperimentOptions& o, controller_file::Family family) {
  ControllerSpec s = family == controller_file::Family::Fuzzy ? controller_file::paper_fuzzy()
                                                              : controller_file::paper_pid();
  s.family = family;
  s.units.gains = o.gain_units;
  s.units.form = o.pid_form;
  s.units.tick_s = o.tick_s;
  s.gains = o.gains;
  s.pid.derivative = o.derivative;
  if (family != controller_file::Family::Pid) {
    s.supervisor.error_scale = o.error_scale;
    s.supervisor.error_rate_scale = o.error_rate_scale;
    s.supervisor.output_scale = o.output_scale;
    s.supervisor.gain_update = o.gain_update;
    s.supervisor.rule_base = o.tables == paper::Tables::Corrected
                                 ? controller_file::RuleBase::PaperCorrected
                                 : controller_file::RuleBase::PaperPrinted;
    s.supervisor.conjunction = o.conjunction;
  }
  return s;
}

std::optional<Experiment> Experiment::create(const robot::RobotModel& model,
                                             const robot::CartesianPathSpec& path,
                                             const ExperimentOptions& options, std::string& error) {
  if (!(options.tick_s > 0.0) || !std::isfinite(options.tick_s) ||
      !std::isfinite(options.initial_error_rad) || !options.gains.finite()) {
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
  // B -> A on the same branch: seeded with the A -> B path's last joints.
  robot::CartesianPathSpec back = path;
  std::swap(back.start_m, back.end_m);
  std::swap(back.start_rotation, back.end_rotation);
  robot::JointPathResult reverse =
      robot::plan_joint_path(model, back, robot::IkSolver::Analytic, planned.position_rad.back());
  return Experiment(model, std::move(planned), std::move(reverse), options);
}

Experiment::Experiment(const robot::RobotModel& model, robot::JointPathResult path,
                       robot::JointPathResult reverse_path, const ExperimentOptions& options)
    : model_(model),
      path_(std::move(path)),
      reverse_path_(std::move(reverse_path)),
      options_(options),
      supervisor_(paper::make_system<double>(options.conjunction, options.tables)) {
  const robot::JointVector links = model_.inertia_diagonal(path_.position_rad.front());
  for (std::size_t i = 0; i < kJoints; ++i)
    nominal_inertia_[i] = links[i] + options_.plant.armature_kgm2[i];
}

const robot::JointPathResult* Experiment::path(const Condition& condition,
                                               std::string& error) const {
  if (!condition.reverse) return &path_;
  if (!reverse_path_.ok()) {
    error = "the reversed path cannot be followed: " + reverse_path_.message;
    return nullptr;
  }
  return &reverse_path_;
}

robot::JointVector Experiment::torque_limit(const Condition& condition) const {
  robot::JointVector limit = model_.effort_limits_nm();
  if (condition.torque_limit_rad_s2 > 0.0)
    for (std::size_t i = 0; i < kJoints; ++i)
      limit[i] = condition.torque_limit_rad_s2 * nominal_inertia_[i];
  return limit;
}

robot::PlantConfig Experiment::plant_config(const Condition& condition) const {
  robot::PlantConfig config = options_.plant;
  config.inertia_scale.fill(condition.payload_scale);
  for (std::size_t i = 0; i < kJoints; ++i)
    config.damping_nms[i] = condition.friction_per_s * nominal_inertia_[i];
  config.torque_limit_nm = torque_limit(condition);
  return config;
}

robot::JointVector Experiment::initial_position(const robot::JointPathResult& path,
                                                const Condition& condition) const {
  robot::JointVector q0 = path.position_rad.front();
  for (double& q : q0)
    q -= condition.initial_error_rad;
  return q0;
}

robot::JointVector Experiment::initial_position() const {
  Condition c;
  c.initial_error_rad = options_.initial_error_rad;
  return initial_position(path_, c);
}

robot::JointVector Experiment::output_limit(const Condition& condition, GainUnits units) const {
  robot::JointVector limit = torque_limit(condition);
  if (units == GainUnits::Acceleration)
    for (std::size_t i = 0; i < kJoints; ++i)
      limit[i] /= nominal_inertia_[i];
  return limit;
}

robot::JointVector Experiment::torque_from_command(const robot::JointVector& u,
                                                   GainUnits units) const noexcept {
  if (units != GainUnits::Acceleration) return u;
  robot::JointVector torque{};
  for (std::size_t i = 0; i < kJoints; ++i)
    torque[i] = nominal_inertia_[i] * u[i];
  return torque;
}

std::array<pid::Pid<double>, kJoints> Experiment::make_pid(const robot::JointVector& limit) const {
  const ControllerSpec spec = default_controller(options_, controller_file::Family::Pid);
  std::array<pid::Pid<double>, kJoints> joints;
  for (std::size_t i = 0; i < kJoints; ++i) {
    const double u_max =
        options_.gain_units == GainUnits::Acceleration ? limit[i] / nominal_inertia_[i] : limit[i];
    joints[i] = pid::Pid<double>(controller_file::pid_config(spec, u_max));
  }
  return joints;
}

std::array<paper::FuzzyPid<double>, kJoints> Experiment::make_fuzzy_pid(
    const robot::JointVector& limit) const {
  const ControllerSpec spec = default_controller(options_, controller_file::Family::Fuzzy);
  std::array<paper::FuzzyPid<double>, kJoints> joints;
  for (std::size_t i = 0; i < kJoints; ++i) {
    const double u_max =
        options_.gain_units == GainUnits::Acceleration ? limit[i] / nominal_inertia_[i] : limit[i];
    joints[i] =
        paper::FuzzyPid<double>(&supervisor_, controller_file::fuzzy_pid_config(spec, u_max));
  }
  return joints;
}

RunResult Experiment::run(const Condition& condition, const ControllerSpec& controller,
                          const RunLimits& limits) const {
  RunResult result;
  auto loop = ClosedLoop::create(*this, condition, controller, result.error);
  if (!loop) return result;
  const std::size_t ticks = loop->samples();
  if (limits.record) result.rows.reserve(ticks * kJoints);
  for (std::size_t k = 0; k < ticks; ++k) {
    const bool advance = k + 1 < ticks;
    const TickResult r = loop->tick(k, advance);
    if (is_fault(r.command.status)) ++result.controller_faults;
    bool diverged = false;
    for (std::size_t i = 0; i < kJoints; ++i) {
      const double e = r.theta_d[i] - r.theta[i];
      if (!(std::fabs(e) <= limits.max_error_rad)) diverged = true;
      if (!limits.record) continue;
      TrajectoryRow row;
      row.t_s = r.t_s;
      row.joint = static_cast<int>(i) + 1;
      row.theta_d = r.theta_d[i];
      row.theta = r.theta[i];
      row.error = e;
      row.error_rate = r.theta_d_dot[i] - r.theta_dot[i];
      row.u = r.command.torque_nm[i];
      const pid::Gains<double> g = loop->controller().file_gains(i);
      row.kp = g.kp;
      row.ki = g.ki;
      row.kd = g.kd;
      result.rows.push_back(row);
    }
    if (diverged) {
      result.diverged = true;
      result.ok = true;
      return result;
    }
    if (r.plant == robot::PlantStatus::Saturated) ++result.saturated_ticks;
    if (r.plant == robot::PlantStatus::InvalidInput ||
        r.plant == robot::PlantStatus::NumericalError) {
      result.error = std::string("plant step failed at t = ") + std::to_string(r.t_s) +
                     " s: " + robot::to_string(r.plant);
      return result;
    }
  }
  result.ok = true;
  return result;
}

double total_itae(const std::vector<TrajectoryRow>& rows, double tick_s) {
  double sum = 0.0;
  for (const TrajectoryRow& r : rows)
    sum += r.t_s * std::fabs(r.error) * tick_s;
  return sum;
}

std::array<JointMetrics, kJoints> run_metrics(const std::vector<TrajectoryRow>& rows,
                                              double tick_s) {
  std::array<JointMetrics, kJoints> out{};
  const std::size_t ticks = rows.size() / kJoints;
  std::vector<double> t(ticks), theta_d(ticks), theta(ticks), err(ticks);
  for (std::size_t i = 0; i < kJoints; ++i) {
    for (std::size_t k = 0; k < ticks; ++k) {
      const TrajectoryRow& row = rows[k * kJoints + i];
      t[k] = row.t_s;
      theta_d[k] = row.theta_d;
      theta[k] = row.theta;
      err[k] = row.error;
    }
    out[i] = joint_metrics(t, theta_d, theta, err, tick_s);
  }
  return out;
}

}  // namespace fuzzypid::sim
