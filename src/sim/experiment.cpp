#include "fuzzypid/sim/experiment.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <utility>

#include "fuzzypid/controller/joint_controllers.hpp"
#include "fuzzypid/paper.hpp"
#include "fuzzypid/robot/ik.hpp"
#include "fuzzypid/robot/path_file.hpp"
#include "fuzzypid/sim/closed_loop.hpp"

namespace fuzzypid::sim {

namespace {

constexpr std::size_t kJoints = robot::kNumJoints;

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Whether `urdf` is the bundled ER50-C20 file (same file, however it is spelled).
bool is_bundled_urdf(const std::string& urdf) {
  std::error_code ec;
  return std::filesystem::equivalent(urdf, robot::default_urdf_path(), ec) && !ec;
}

}  // namespace

ControllerSpec default_controller(const ExperimentOptions& o, ControllerSpec paper) {
  ControllerSpec s = std::move(paper);
  s.units.gains = o.gain_units;
  s.units.form = o.pid_form;
  s.units.tick_s = o.tick_s;
  s.gains = o.gains;
  s.pid.derivative = o.derivative;
  if (controller::family_traits(s.family).supervised()) {
    s.supervisor.error_scale = o.error_scale;
    s.supervisor.error_rate_scale = o.error_rate_scale;
    s.supervisor.output_scale = o.output_scale;
    s.supervisor.gain_update = o.gain_update;
    s.supervisor.rule_base = o.tables;
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
  // The closed-form solver where the model is the Table 1 geometry, seeded for the first sample
  // with the paper's start joints so the path takes the same (elbow-up, wrist-flipped) branch the
  // paper's vector suggests; KDL's joint-limited Newton-Raphson from the middle of the limits for
  // any other arm.
  const robot::InverseKinematics ik(model);
  const robot::IkSolver solver =
      ik.has_analytic() ? robot::IkSolver::Analytic : robot::IkSolver::KdlNr;
  const robot::JointVector seed =
      ik.has_analytic() ? robot::kPaperStartJoints : robot::default_ik_seed(model);
  robot::JointPathResult planned = robot::plan_joint_path(ik, model, path, solver, seed);
  if (!planned.ok()) {
    error = "the line A -> B cannot be followed: " + planned.message;
    if (planned.first_failure < planned.poses.size()) {
      const robot::Pose& p = planned.poses[planned.first_failure];
      error += " (t = " + num(planned.time_s[planned.first_failure]) + " s, tool at (" +
               num(p.position_m.x()) + ", " + num(p.position_m.y()) + ", " + num(p.position_m.z()) +
               ") m; solver " +
               (ik.has_analytic() ? "closed-form IK" : "KDL Newton-Raphson (joint-limited)") +
               "); another arm than the ER50-C20 needs its own path (--path FILE)";
    }
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
      robot::plan_joint_path(ik, model, back, solver, planned.position_rad.back());
  return Experiment(model, std::move(planned), std::move(reverse), options);
}

std::optional<Experiment> Experiment::create(const RobotSetup& setup,
                                             const ExperimentOptions& options, std::string& error) {
  if (const std::string bad = setup.validate(); !bad.empty()) {
    error = bad;
    return std::nullopt;
  }
  const std::string urdf = setup.urdf.empty() ? robot::default_urdf_path() : setup.urdf;
  robot::LoadResult loaded = robot::RobotModel::load(urdf, setup.base_link, setup.tip_link);
  if (!loaded.model) {
    error = "cannot load " + urdf + ": " + loaded.error;
    return std::nullopt;
  }
  const robot::RobotModel& model = *loaded.model;
  ExperimentOptions o = options;
  o.tick_s = setup.tick_s;
  if (setup.armature_kgm2) {
    o.plant.armature_kgm2 = *setup.armature_kgm2;
  } else if (!is_bundled_urdf(urdf)) {
    o.plant.armature_kgm2 = robot::JointVector{};
  } else {
    o.plant.armature_kgm2 = robot::kEr50ArmatureKgm2;
  }
  std::optional<Experiment> ex;
  if (setup.path.empty()) {
    robot::CartesianPathSpec spec = robot::paper_path_spec();
    if (setup.start_m)
      spec.start_m = Eigen::Vector3d((*setup.start_m)[0], (*setup.start_m)[1], (*setup.start_m)[2]);
    if (setup.end_m)
      spec.end_m = Eigen::Vector3d((*setup.end_m)[0], (*setup.end_m)[1], (*setup.end_m)[2]);
    // 5 s rounded to a whole number of ticks (exactly 5 s at 50 ms, 10 ms, 1 ms, ...).
    spec.samples = static_cast<std::size_t>(std::llround(spec.duration_s / setup.tick_s)) + 1;
    if (spec.samples < 2) spec.samples = 2;
    spec.duration_s = static_cast<double>(spec.samples - 1) * setup.tick_s;
    ex = create(model, spec, o, error);
  } else {
    robot::PathTable table;
    if (!robot::load_path_csv(setup.path, table, error)) return std::nullopt;
    if (setup.ik_seed_rad && table.kind == robot::PathKind::Joint) {
      error = "--ik-seed (condition key ik_seed) applies only to a Cartesian path file; " +
              setup.path + " is a joint path (t_s,q1_rad,...,q6_rad): its rows are the joints";
      return std::nullopt;
    }
    const robot::InverseKinematics ik(model);
    robot::JointPathResult planned = robot::joint_path_from_table(
        ik, model, table, setup.tick_s, setup.ik_seed_rad.value_or(robot::default_ik_seed(model)));
    if (!planned.ok()) {
      error = planned.message;
      return std::nullopt;
    }
    robot::JointPathResult back = robot::reversed(planned);
    ex = Experiment(model, std::move(planned), std::move(back), o);
  }
  if (!ex) return std::nullopt;
  ex->setup_ = setup;
  ex->urdf_file_ = urdf;
  return ex;
}

robot::RobotModel Experiment::plant_model(const Condition& condition) const {
  if (condition.payload_kg > 0.0) return model_.with_payload(condition.payload_kg);
  return model_;
}

std::optional<ExperimentSet> ExperimentSet::create(const std::vector<Condition>& conditions,
                                                   const ExperimentOptions& options,
                                                   std::string& error) {
  ExperimentSet set;
  std::vector<const RobotSetup*> setups;
  for (const Condition& c : conditions) {
    std::size_t found = setups.size();
    for (std::size_t i = 0; i < setups.size(); ++i)
      if (*setups[i] == c.robot) found = i;
    if (found == setups.size()) {
      auto ex = Experiment::create(c.robot, options, error);
      if (!ex) {
        error = "condition " + c.name + ": " + error;
        return std::nullopt;
      }
      set.experiments_.push_back(std::make_shared<const Experiment>(std::move(*ex)));
      setups.push_back(&c.robot);
    }
    set.index_.push_back(found);
    if (std::string bad = set.experiments_[found]->refusal(c); !bad.empty()) {
      error = "condition " + c.name + ": " + bad;
      return std::nullopt;
    }
  }
  return set;
}

Experiment::Experiment(const robot::RobotModel& model, robot::JointPathResult path,
                       robot::JointPathResult reverse_path, const ExperimentOptions& options)
    : model_(model),
      path_(std::move(path)),
      reverse_path_(std::move(reverse_path)),
      options_(options),
      supervisor_(paper::make_system<double>(options.conjunction, options.tables)) {
  robot::RobotData data(model_);
  const robot::JointVector links = model_.inertia_diagonal(path_.position_rad.front(), data);
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

std::string Experiment::refusal(const Condition& condition) const {
  if (std::string bad = condition.validate(); !bad.empty()) return bad;
  std::string error;
  if (path(condition, error) == nullptr) return error;
  for (std::size_t i = 0; i < kJoints; ++i)
    if (condition.effects.joint_resonance_hz[i] > 0.0 && !(armature_kgm2()[i] > 0.0))
      return "joint_resonance_hz needs an armature > 0 on joint " + std::to_string(i + 1) +
             " (the motor side of the two-mass joint; --armature or the key armature)";
  return {};
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
  config.coupling = condition.dynamics;
  config.gravity = condition.gravity;
  const JointEffects& e = condition.effects;
  if (e.plant_step_s > 0.0) config.substep_s = config.coupled_substep_s = e.plant_step_s;
  config.delay_s = e.delay_s;
  config.torque_bandwidth_hz = e.torque_bandwidth_hz;
  config.encoder_counts = e.encoder_counts;
  config.coulomb_nm = e.coulomb_nm;
  config.stribeck_nm = e.stribeck_nm;
  if (e.stribeck_velocity_rad_s > 0.0) config.stribeck_velocity_rad_s = e.stribeck_velocity_rad_s;
  if (e.coulomb_smoothing_rad_s > 0.0) config.coulomb_smoothing_rad_s = e.coulomb_smoothing_rad_s;
  config.joint_resonance_hz = e.joint_resonance_hz;
  config.joint_damping_ratio = e.joint_damping_ratio;
  config.backlash_rad = e.backlash_rad;
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
  const ControllerSpec spec = default_controller(options_, controller::paper_pid());
  std::array<pid::Pid<double>, kJoints> joints;
  for (std::size_t i = 0; i < kJoints; ++i) {
    const double u_max =
        options_.gain_units == GainUnits::Acceleration ? limit[i] / nominal_inertia_[i] : limit[i];
    joints[i] = pid::Pid<double>(controller::pid_config(spec, i, u_max));
  }
  return joints;
}

std::array<paper::FuzzyPid<double>, kJoints> Experiment::make_fuzzy_pid(
    const robot::JointVector& limit) const {
  const ControllerSpec spec = default_controller(options_, controller::paper_fuzzy());
  std::array<paper::FuzzyPid<double>, kJoints> joints;
  for (std::size_t i = 0; i < kJoints; ++i) {
    const double u_max =
        options_.gain_units == GainUnits::Acceleration ? limit[i] / nominal_inertia_[i] : limit[i];
    joints[i] = paper::FuzzyPid<double>(&supervisor_, controller::fuzzy_pid_config(spec, i, u_max));
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
  // The bounds and K0 exactly as each joint holds them (continuous SI form).
  const bool supervised = controller::family_traits(controller.family).supervised();
  std::array<supervisor::FuzzyPidConfig<double>, kJoints> joint_bounds;
  for (std::size_t i = 0; i < kJoints; ++i)
    joint_bounds[i] =
        controller::fuzzy_pid_config(controller, i, std::numeric_limits<double>::infinity());
  const auto at_bound = [](double k, double k0, double lo, double hi) {
    return (k <= lo && k0 > lo) || (k >= hi && k0 < hi);
  };
  const robot::JointVector torque_limit_nm = torque_limit(condition);
  FaultMonitor faults(limits.divergence_rad, model_.lower_limits_rad(), model_.upper_limits_rad());
  for (std::size_t k = 0; k < ticks; ++k) {
    const bool advance = k + 1 < ticks;
    const TickResult r = loop->tick(k, advance);
    const bool controller_fault = is_fault(r.command.status);
    if (controller_fault) ++result.controller_faults;
    const std::array<bool, kJoints> at_limit =
        at_torque_limit(loop->plant().applied_torque(), loop->plant().saturated(), torque_limit_nm);
    if (faults.observe(r.t_s, r.theta_d, r.theta, loop->plant().applied_torque(), at_limit) ||
        controller_fault)
      ++result.fault_ticks;
    for (std::size_t i = 0; supervised && i < kJoints; ++i) {
      if (r.command.joint_status[i] == Status::NoRuleFired) ++result.no_rule_ticks[i];
      const pid::Gains<double> g = loop->controller().gains(i);
      const supervisor::FuzzyPidConfig<double>& bounds = joint_bounds[i];
      const auto& k0 = bounds.pid.gains;
      if (at_bound(g.kp, k0.kp, bounds.gain_min.kp, bounds.gain_max.kp) ||
          at_bound(g.ki, k0.ki, bounds.gain_min.ki, bounds.gain_max.ki) ||
          at_bound(g.kd, k0.kd, bounds.gain_min.kd, bounds.gain_max.kd))
        ++result.clamped_gain_ticks[i];
    }
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
      row.u = r.command.output[i];
      const pid::Gains<double> g = loop->controller().file_gains(i);
      row.kp = g.kp;
      row.ki = g.ki;
      row.kd = g.kd;
      row.tau_nm = loop->plant().applied_torque()[i];
      row.omega_rad_s = r.theta_dot[i];
      row.saturated = at_limit[i];
      result.rows.push_back(row);
    }
    if (diverged) {
      result.tracking_faults = faults.faults();
      result.diverged = true;
      result.ok = true;
      return result;
    }
    if (r.plant == robot::PlantStatus::Saturated) ++result.saturated_ticks;
    if (r.plant == robot::PlantStatus::InvalidInput ||
        r.plant == robot::PlantStatus::NumericalError) {
      result.tracking_faults = faults.faults();
      result.error = std::string("plant step failed at t = ") + std::to_string(r.t_s) +
                     " s: " + robot::to_string(r.plant);
      return result;
    }
  }
  result.tracking_faults = faults.faults();
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

std::array<DriveMetrics, kJoints> run_drive_metrics(const std::vector<TrajectoryRow>& rows) {
  std::array<DriveMetrics, kJoints> out{};
  const std::size_t ticks = rows.size() / kJoints;
  std::vector<double> t(ticks), u(ticks), tau(ticks);
  std::vector<char> saturated(ticks);
  for (std::size_t i = 0; i < kJoints; ++i) {
    for (std::size_t k = 0; k < ticks; ++k) {
      const TrajectoryRow& row = rows[k * kJoints + i];
      t[k] = row.t_s;
      u[k] = row.u;
      tau[k] = row.tau_nm;
      saturated[k] = row.saturated ? 1 : 0;
    }
    out[i] = drive_metrics(t, u, tau, saturated);
  }
  return out;
}

TcpTrack tcp_track(const robot::RobotModel& model, const std::vector<TrajectoryRow>& rows) {
  TcpTrack track;
  const std::size_t ticks = rows.size() / kJoints;
  track.t_s.reserve(ticks);
  track.desired_m.reserve(ticks);
  track.actual_m.reserve(ticks);
  robot::RobotData data(model);
  for (std::size_t k = 0; k < ticks; ++k) {
    robot::JointVector qd{}, q{};
    for (std::size_t i = 0; i < kJoints; ++i) {
      qd[i] = rows[k * kJoints + i].theta_d;
      q[i] = rows[k * kJoints + i].theta;
    }
    track.t_s.push_back(rows[k * kJoints].t_s);
    track.desired_m.push_back(model.forward_kinematics(qd, data).position_m);
    track.actual_m.push_back(model.forward_kinematics(q, data).position_m);
  }
  return track;
}

RunSummary summarize(const std::array<JointMetrics, kJoints>& metrics,
                     const std::array<DriveMetrics, kJoints>& drive) {
  RunSummary s;
  for (const auto& j : metrics) {
    s.itae += j.itae;
    s.max_overshoot_pct = std::max(s.max_overshoot_pct, j.overshoot_pct);
    s.max_settling_s = std::max(s.max_settling_s, j.settling_time_s);
    s.max_error_after_1s_rad = std::max(s.max_error_after_1s_rad, j.max_abs_error_after_1s_rad);
  }
  for (const auto& d : drive) {
    s.max_reversals_pct = std::max(s.max_reversals_pct, d.reversals_pct);
    s.max_sign_changes_pct = std::max(s.max_sign_changes_pct, d.sign_changes_pct);
    s.max_saturated_pct = std::max(s.max_saturated_pct, d.saturated_pct);
  }
  return s;
}

TcpErrorMetrics tcp_error_metrics(const TcpTrack& track) {
  TcpErrorMetrics m;
  const std::size_t n = std::min(track.desired_m.size(), track.actual_m.size());
  if (n == 0) return m;
  double sum_sq = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double d_mm = (track.actual_m[k] - track.desired_m[k]).norm() * 1e3;
    m.max_mm = std::max(m.max_mm, d_mm);
    sum_sq += d_mm * d_mm;
  }
  m.rms_mm = std::sqrt(sum_sq / static_cast<double>(n));
  return m;
}

}  // namespace fuzzypid::sim
