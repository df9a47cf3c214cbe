// The section 6 experiment: the ER50-C20 following the A -> B path (or B -> A) under a controller
// described by a controller file, on the joint plant, one controller tick at a time
// (closed_loop.hpp), for any condition (condition.hpp).
//
// ExperimentOptions holds the settings of the plant and of the paper's default controllers (what
// sim_ab runs without --controller); every modelling choice the paper leaves open is a named field
// with a documented default (docs/reproduction.md discusses each):
//   - gain_units:   the gains act on an inertia-normalised loop (u in rad/s², torque
//                   tau_i = J^_i u_i with J^_i the nominal joint inertia at the path start) or
//                   directly as torque gains (u in N·m);
//   - pid_form:     per-tick gains (u = Kp e + Ki sum(e) + Kd (e_k - e_{k-1}), the textbook
//                   discrete form) or continuous-time gains; per-tick gains are converted by
//                   controller::to_continuous (Ki/dt, Kd dt);
//   - derivative:   de/dt from the measured velocities (Eq. 2) or from successive errors;
//   - gain_update, error_scale, error_rate_scale, output_scale: how the supervisor's
//                   dKp, dKi, dKd reach the PID (supervisor/fuzzy_pid.hpp);
//   - initial_error_rad: the default condition's start error (the transient of Fig. 10).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fuzzypid/controller/controller_spec.hpp"
#include "fuzzypid/paper.hpp"
#include "fuzzypid/pid/gains.hpp"
#include "fuzzypid/pid/pid.hpp"
#include "fuzzypid/robot/path.hpp"
#include "fuzzypid/robot/plant.hpp"
#include "fuzzypid/robot/robot_model.hpp"
#include "fuzzypid/robot/types.hpp"
#include "fuzzypid/sim/condition.hpp"
#include "fuzzypid/sim/faults.hpp"
#include "fuzzypid/sim/metrics.hpp"
#include "fuzzypid/supervisor/fuzzy_pid.hpp"

namespace fuzzypid::sim {

using GainUnits = controller::GainUnits;
using PidForm = controller::PidForm;
using controller::ControllerSpec;

struct ExperimentOptions {
  double tick_s = 0.05;  // section 6: sampled once every 0.05 s
  // The paper's nominal gains Kp = 4, Ki = 0.001, Kd = 100, in the units pid_form names.
  pid::Gains<double> gains = paper::kNominalGains<double>;
  GainUnits gain_units = GainUnits::Acceleration;
  PidForm pid_form = PidForm::PerTick;
  pid::DerivativeSource derivative = pid::DerivativeSource::Rates;
  supervisor::GainUpdate gain_update = supervisor::GainUpdate::Absolute;
  double error_scale = 1.0;       // Ke: universe units per rad
  double error_rate_scale = 1.0;  // Kec: universe units per rad/s
  std::array<double, 3> output_scale = {1.0, 1.0, 1.0};
  paper::Tables tables = paper::Tables::Printed;
  fuzzy::Conjunction conjunction = fuzzy::Conjunction::Minimum;
  double initial_error_rad = 0.05;  // of the default condition
  std::uint64_t noise_seed = 1;     // of the default condition
  robot::PlantConfig plant{};       // condition fields are applied on top
};

// `paper` (controller::paper_pid() or paper_fuzzy()) with the options' units, gains and, for a
// supervised family, supervisor settings.
[[nodiscard]] ControllerSpec default_controller(const ExperimentOptions& options,
                                                ControllerSpec paper);

// One row of trajectory.csv: one joint at one tick under one controller.
struct TrajectoryRow {
  double t_s = 0.0;
  int joint = 0;                        // 1..6
  double theta_d = 0.0;                 // rad
  double theta = 0.0;                   // rad, true (noise-free) joint angle
  double error = 0.0;                   // theta_d - theta, rad
  double error_rate = 0.0;              // theta_d dot - theta dot, rad/s
  double u = 0.0;                       // controller output (rad/s² or N·m, see gain units)
  double kp = 0.0, ki = 0.0, kd = 0.0;  // gains of this tick, in the controller file's units
  // The torque the plant received over the step that starts at this sample, after its limits
  // (robot::JointPlant::applied_torque()); the last sample, which starts no step, repeats the
  // one before. N·m.
  double tau_nm = 0.0;
  double omega_rad_s = 0.0;  // true joint velocity at the sample
  // tau_nm sat at the joint's torque limit: the plant clamped it, or it lies on the limit
  // within 1e-9 relative (the controller's output limit, the plant's over J^_i, held it there).
  bool saturated = false;
};

struct RunResult {
  bool ok = false;
  std::string error;                // set when !ok
  std::vector<TrajectoryRow> rows;  // tick-major, joints 1..6 within a tick
  std::size_t controller_faults = 0;
  std::size_t saturated_ticks = 0;  // ticks in which the plant clamped at least one torque
  // Per joint: ticks on which the supervisor fired no rule (the gains stayed where they were:
  // a rule base with a coverage gap runs as a fixed PID there), and ticks on which a retuned gain
  // sat at a bound of the file's [bounds] that K0 is not at (the supervisor asked for more or
  // less than the bounds allow).
  std::array<std::size_t, robot::kNumJoints> no_rule_ticks{};
  std::array<std::size_t, robot::kNumJoints> clamped_gain_ticks{};
  bool diverged = false;  // stopped early: |e| exceeded RunLimits::max_error_rad
  // Joints that diverged (|e| > RunLimits::divergence_rad) or left the URDF's joint limits, tick
  // by tick over the ticks run (faults.hpp); the run goes on through them.
  TrackingFaults tracking_faults{};
  // Ticks on which the controller faulted or a joint did (tracking_faults): metrics.csv `faults`.
  std::size_t fault_ticks = 0;
};

struct RunLimits {
  // Stop the run (diverged) once any joint's |e| exceeds this; +inf never stops.
  double max_error_rad = std::numeric_limits<double>::infinity();
  // A joint whose |e| exceeds this is counted in RunResult::tracking_faults (the run goes on).
  double divergence_rad = kDefaultDivergenceRad;
  bool record = true;  // fill RunResult::rows (metrics need them)
};

class Experiment {
 public:
  // Loads the setup's URDF (base and tip links as named), chooses the armature (the ER50's
  // estimates for the bundled URDF, else 0, unless the setup gives it) and plans the joint path at
  // the setup's tick: the section 6 line A -> B (closed-form IK where the model is the Table 1
  // geometry, KDL otherwise) or the setup's path file (robot/path_file.hpp). The options' tick
  // and armature are replaced by the setup's. Returns nullopt with a message naming the file,
  // row or pose that failed.
  static std::optional<Experiment> create(const RobotSetup& setup, const ExperimentOptions& options,
                                          std::string& error);

  // Plans the joint path A -> B (closed-form IK) and B -> A, and evaluates the nominal inertia J^
  // at A. Returns an error message instead when the A -> B path cannot be planned (a B -> A path
  // that cannot be planned is reported when a reversed condition is run).
  static std::optional<Experiment> create(const robot::RobotModel& model,
                                          const robot::CartesianPathSpec& path,
                                          const ExperimentOptions& options, std::string& error);

  // Runs one controller on one condition from its initial state.
  RunResult run(const Condition& condition, const ControllerSpec& controller,
                const RunLimits& limits = {}) const;

  // The pieces a closed loop is built from.
  //
  // The planned path of the condition (A -> B, or B -> A when reversed); nullptr with `error`
  // set when the reversed path could not be planned.
  const robot::JointPathResult* path(const Condition& condition, std::string& error) const;
  // Why this experiment cannot run the condition, or "" when it can: the condition's own
  // validate(), a reversed path that could not be planned, a gear resonance on a joint without
  // armature (the motor side of the two-mass joint). ClosedLoop::create refuses the same, and
  // ExperimentSet::create refuses every condition of its list before anything runs.
  [[nodiscard]] std::string refusal(const Condition& condition) const;
  // Torque limit of each joint (N·m): the URDF effort limits, or the condition's limit times J^_i.
  robot::JointVector torque_limit(const Condition& condition) const;
  // The plant configuration of the condition (payload, friction, torque limits applied).
  robot::PlantConfig plant_config(const Condition& condition) const;
  // Where the joints start on `path`: its first sample minus the condition's initial error.
  robot::JointVector initial_position(const robot::JointPathResult& path,
                                      const Condition& condition) const;
  // The controller's output limits (torque limit / J^_i with acceleration units).
  robot::JointVector output_limit(const Condition& condition, GainUnits units) const;
  // The torque a controller output asks for: J^_i u_i with acceleration units, u_i else.
  robot::JointVector torque_from_command(const robot::JointVector& u,
                                         GainUnits units) const noexcept;

  // Compatibility for the real-time loop and the soak test: the A -> B path, the default
  // condition's start, the paper's controllers with the options' settings.
  const robot::JointPathResult& path() const noexcept { return path_; }
  robot::JointVector initial_position() const;
  robot::JointVector torque_from_command(const robot::JointVector& u) const noexcept {
    return torque_from_command(u, options_.gain_units);
  }
  std::array<pid::Pid<double>, robot::kNumJoints> make_pid(
      const robot::JointVector& torque_limit) const;
  // The fuzzy controllers point to this Experiment's supervisor: it must outlive them.
  std::array<paper::FuzzyPid<double>, robot::kNumJoints> make_fuzzy_pid(
      const robot::JointVector& torque_limit) const;

  // The model the plant of `condition` integrates: the robot with the condition's payload mass at
  // the flange (the controller's nominal model, model(), never has it).
  robot::RobotModel plant_model(const Condition& condition) const;
  // The setup the experiment was built from (urdf and path as given), the URDF file loaded and
  // the reflected motor inertia used.
  const RobotSetup& setup() const noexcept { return setup_; }
  const std::string& urdf_file() const noexcept { return urdf_file_; }
  const robot::JointVector& armature_kgm2() const noexcept { return options_.plant.armature_kgm2; }

  const robot::JointVector& nominal_inertia() const noexcept { return nominal_inertia_; }
  const ExperimentOptions& options() const noexcept { return options_; }
  const robot::RobotModel& model() const noexcept { return model_; }
  std::size_t ticks() const noexcept { return path_.time_s.size(); }

 private:
  Experiment(const robot::RobotModel& model, robot::JointPathResult path,
             robot::JointPathResult reverse_path, const ExperimentOptions& options);

  robot::RobotModel model_;
  RobotSetup setup_;
  std::string urdf_file_;
  robot::JointPathResult path_;
  robot::JointPathResult reverse_path_;
  ExperimentOptions options_;
  robot::JointVector nominal_inertia_{};
  paper::System<double> supervisor_{};  // of make_fuzzy_pid
};

// The experiments of a list of conditions: one per distinct RobotSetup, built once (loading URDFs
// and planning paths allocates and takes milliseconds), shared by the conditions that name it.
// Experiments never move once built, so closed loops may point into them.
class ExperimentSet {
 public:
  // Builds the experiment of every condition's setup with `options`' controller settings;
  // nullopt with `error` set when a setup cannot be built or its experiment cannot run one of the
  // conditions (Experiment::refusal).
  static std::optional<ExperimentSet> create(const std::vector<Condition>& conditions,
                                             const ExperimentOptions& options, std::string& error);
  // The experiment of conditions[k] (the list given to create()).
  const Experiment& of(std::size_t k) const noexcept { return *experiments_[index_[k]]; }
  std::size_t size() const noexcept { return experiments_.size(); }
  const Experiment& experiment(std::size_t i) const noexcept { return *experiments_[i]; }

 private:
  std::vector<std::shared_ptr<const Experiment>> experiments_;
  std::vector<std::size_t> index_;
};

// ITAE summed over the six joints of a run's rows.
[[nodiscard]] double total_itae(const std::vector<TrajectoryRow>& rows, double tick_s);
// The metrics of each joint of a run (rows of one run, tick-major).
[[nodiscard]] std::array<JointMetrics, robot::kNumJoints> run_metrics(
    const std::vector<TrajectoryRow>& rows, double tick_s);
// The drive metrics (metrics.hpp) of each joint of a run.
[[nodiscard]] std::array<DriveMetrics, robot::kNumJoints> run_drive_metrics(
    const std::vector<TrajectoryRow>& rows);
// A run over the six joints in one line: ITAE summed, every other figure its worst joint's (the
// drive figures stay 0 when no drive metrics are given).
struct RunSummary {
  double itae = 0.0;
  double max_overshoot_pct = 0.0;
  double max_settling_s = 0.0;
  double max_error_after_1s_rad = 0.0;
  double max_reversals_pct = 0.0;
  double max_sign_changes_pct = 0.0;
  double max_saturated_pct = 0.0;
};
[[nodiscard]] RunSummary summarize(const std::array<JointMetrics, robot::kNumJoints>& metrics,
                                   const std::array<DriveMetrics, robot::kNumJoints>& drive = {});

// The tool's path: at each tick of a run, the forward kinematics of the reference joints
// (desired) and of the true joints (actual), m, in the chain's root frame.
struct TcpTrack {
  std::vector<double> t_s;
  std::vector<Eigen::Vector3d> desired_m, actual_m;
};
[[nodiscard]] TcpTrack tcp_track(const robot::RobotModel& model,
                                 const std::vector<TrajectoryRow>& rows);
// The tool's path error |p_actual - p_desired| over the ticks: its maximum and RMS, mm.
struct TcpErrorMetrics {
  double max_mm = 0.0;
  double rms_mm = 0.0;
};
[[nodiscard]] TcpErrorMetrics tcp_error_metrics(const TcpTrack& track);

}  // namespace fuzzypid::sim
