// The section 6 experiment: the ER50-C20 following the A -> B path under a fixed PID or a fuzzy
// PID, on the joint plant, one controller tick at a time.
//
// Every modelling choice the paper leaves open is a named field of ExperimentOptions with a
// documented default (docs/reproduction.md discusses each):
//   - gain_units:   the paper's gains act on an inertia-normalised loop (u in rad/s², torque
//                   tau_i = J^_i u_i with J^_i the nominal joint inertia at the path start) or
//                   directly as torque gains (u in N·m);
//   - pid_form:     per-tick gains (u = Kp e + Ki sum(e) + Kd (e_k - e_{k-1}), the textbook
//                   discrete form) or continuous-time gains (u = Kp e + Ki int(e dt) + Kd de/dt);
//                   per-tick gains are converted to continuous ones as Ki/dt and Kd dt;
//   - derivative:   de/dt from the measured velocities (Eq. 2) or from successive errors;
//   - gain_update, error_scale, error_rate_scale, output_scale: how the supervisor's
//                   dKp, dKi, dKd reach the PID (control/fuzzy_pid.hpp);
//   - initial_error_rad: the robot starts at rest at theta_d(0) - initial_error, which produces
//                   the transient of Fig. 10.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "fuzzypid/control/fuzzy_pid.hpp"
#include "fuzzypid/paper.hpp"
#include "fuzzypid/pid/gains.hpp"
#include "fuzzypid/robot/path.hpp"
#include "fuzzypid/robot/plant.hpp"
#include "fuzzypid/robot/robot_model.hpp"
#include "fuzzypid/robot/types.hpp"
#include "fuzzypid/sim/scenario.hpp"

namespace fuzzypid::sim {

enum class GainUnits : std::uint8_t { Acceleration, Torque };
enum class PidForm : std::uint8_t { PerTick, Continuous };
enum class ControllerKind : std::uint8_t { Pid, Fuzzy, PidTuned };

[[nodiscard]] const char* to_string(GainUnits g) noexcept;
[[nodiscard]] const char* to_string(PidForm f) noexcept;
// "pid", "fuzzy", "pid-tuned": the names used in the CSV files.
[[nodiscard]] const char* to_string(ControllerKind c) noexcept;

struct ExperimentOptions {
  double tick_s = 0.05;  // section 6: sampled once every 0.05 s
  // The paper's nominal gains Kp = 4, Ki = 0.001, Kd = 100, in the units pid_form names.
  pid::Gains<double> gains = {4.0, 0.001, 100.0};
  GainUnits gain_units = GainUnits::Acceleration;
  PidForm pid_form = PidForm::PerTick;
  pid::DerivativeSource derivative = pid::DerivativeSource::Rates;
  control::GainUpdate gain_update = control::GainUpdate::Absolute;
  double error_scale = 1.0;       // Ke: universe units per rad
  double error_rate_scale = 1.0;  // Kec: universe units per rad/s
  std::array<double, 3> output_scale = {1.0, 1.0, 1.0};
  paper::Tables tables = paper::Tables::Printed;
  fuzzy::Conjunction conjunction = fuzzy::Conjunction::Minimum;
  double initial_error_rad = 0.05;  // every joint starts this far behind theta_d(0)
  std::uint64_t noise_seed = 1;     // for scenarios with measurement noise
  robot::PlantConfig plant{};       // scenario fields are applied on top
};

// One row of trajectory.csv: one joint at one tick under one controller.
struct TrajectoryRow {
  double t_s = 0.0;
  int joint = 0;                        // 1..6
  double theta_d = 0.0;                 // rad
  double theta = 0.0;                   // rad, true (noise-free) joint angle
  double error = 0.0;                   // theta_d - theta, rad
  double error_rate = 0.0;              // theta_d dot - theta dot, rad/s
  double u = 0.0;                       // controller output (rad/s² or N·m, see gain_units)
  double kp = 0.0, ki = 0.0, kd = 0.0;  // gains of this tick, in the paper's units (pid_form)
};

struct RunResult {
  bool ok = false;
  std::string error;                // set when !ok
  std::vector<TrajectoryRow> rows;  // tick-major, joints 1..6 within a tick
  std::size_t controller_faults = 0;
  std::size_t saturated_ticks = 0;  // ticks in which the plant clamped at least one torque
};

class Experiment {
 public:
  // Plans the joint path (closed-form IK) and evaluates the nominal inertia J^ at its start.
  // Returns an error message instead when the path cannot be planned.
  static std::optional<Experiment> create(const robot::RobotModel& model,
                                          const robot::CartesianPathSpec& path,
                                          const ExperimentOptions& options, std::string& error);

  // Runs one controller on one scenario from the initial state. `gains` are the fixed PID's (or
  // the fuzzy PID's nominal K0) in the paper's units; by default the options' gains.
  RunResult run(const Scenario& scenario, ControllerKind kind,
                const std::optional<pid::Gains<double>>& gains = std::nullopt) const;

  // The pieces run() builds before its first tick, public so that a real-time loop or a soak test
  // runs exactly the A/B simulation's settings.
  //
  // Torque limit of each joint in the scenario (N·m): the URDF effort limits, or the scenario's
  // acceleration limit times J^_i.
  robot::JointVector torque_limit(const Scenario& scenario) const;
  // The plant configuration of the scenario (inertia scale, damping, torque limits applied).
  robot::PlantConfig plant_config(const Scenario& scenario) const;
  // Where the joints start: theta_d(0) - initial_error_rad, at rest.
  robot::JointVector initial_position() const;
  // The six controllers of a run, with output limits matching `torque_limit` (in the units of
  // gain_units) and `gains` in the paper's units (default: the options' gains).
  std::array<pid::Pid<double>, robot::kNumJoints> make_pid(
      const robot::JointVector& torque_limit,
      const std::optional<pid::Gains<double>>& gains = std::nullopt) const;
  // The fuzzy controllers point to this Experiment's supervisor (supervisor()): the Experiment
  // must outlive them.
  std::array<paper::FuzzyPid<double>, robot::kNumJoints> make_fuzzy_pid(
      const robot::JointVector& torque_limit,
      const std::optional<pid::Gains<double>>& gains = std::nullopt) const;
  // The torque a controller output asks for: J^_i u_i with GainUnits::Acceleration, u_i else.
  robot::JointVector torque_from_command(const robot::JointVector& u) const noexcept;
  // Gains of the PID's continuous SI form expressed in the paper's units (for logging).
  pid::Gains<double> to_paper_units(const pid::Gains<double>& g) const noexcept;

  const robot::JointPathResult& path() const noexcept { return path_; }
  const robot::JointVector& nominal_inertia() const noexcept { return nominal_inertia_; }
  const ExperimentOptions& options() const noexcept { return options_; }
  // The paper's supervisor with the options' conjunction and tables, shared by the fuzzy joints.
  const paper::System<double>& supervisor() const noexcept { return supervisor_; }
  std::size_t ticks() const noexcept { return path_.time_s.size(); }

 private:
  Experiment(const robot::RobotModel& model, robot::JointPathResult path,
             const ExperimentOptions& options);

  // The paper-unit gains converted to the PID's continuous SI form.
  pid::Gains<double> to_continuous(const pid::Gains<double>& g) const noexcept;
  std::array<pid::Config<double>, robot::kNumJoints> pid_configs(
      const robot::JointVector& torque_limit, const pid::Gains<double>& paper_gains) const;

  robot::RobotModel model_;
  robot::JointPathResult path_;
  ExperimentOptions options_;
  robot::JointVector nominal_inertia_{};
  paper::System<double> supervisor_{};
};

// ITAE summed over the six joints of a run's rows (the tuning objective).
[[nodiscard]] double total_itae(const std::vector<TrajectoryRow>& rows, double tick_s);

struct TuningResult {
  pid::Gains<double> gains;  // paper units
  double itae = 0.0;
  std::size_t evaluations = 0;
};

// Tunes the fixed PID's three gains for `scenario` by Nelder-Mead on log10 of the gains,
// minimising the summed ITAE, starting from the options' gains.
[[nodiscard]] TuningResult tune_pid(const Experiment& experiment, const Scenario& scenario);

}  // namespace fuzzypid::sim
