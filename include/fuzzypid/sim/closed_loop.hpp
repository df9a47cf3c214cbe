// One closed loop: the path, the six joints' controller, the torque and the plant, advanced one
// controller tick at a time. sim::Experiment::run, the real-time loop and the soak test all tick
// this one object, so they simulate the same thing.
//
// A tick at path sample k (theta_d, theta_d dot) -> measured angles and velocities (true state plus
// the condition's Gaussian noise) -> controller -> torque (J^_i u_i with acceleration units) ->
// plant over one tick with the condition's contact disturbance held. create() allocates; tick()
// does not allocate, throw or print.
//
// Continuous joints (no position limits in the URDF): the reference given to the controller is
// moved by a multiple of 2 pi to within (-pi, pi] of the measured angle, so the controller's error
// is wrapped to (-pi, pi] and a path crossing +/-pi never makes the joint unwind a full turn.
// A controller file asking for gravity feed-forward ([feedforward] gravity = true) gets
// g^(theta_d) of the nominal model (no payload) added to its torque.
//
// Fault injection: a TickInjection given to tick() reaches between those steps -- a setpoint jump,
// corrupted measurements, another dt for the controller than the time the plant advances, an
// extra disturbance torque -- and reset_plant() puts the plant anywhere. A default TickInjection
// changes nothing: tick(sample(k), {}, advance) is tick(k, advance) bit for bit. cyclic_sample()
// plays the path back and forth without end, for runs longer than the path.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "fuzzypid/controller/joint_controllers.hpp"
#include "fuzzypid/robot/plant.hpp"
#include "fuzzypid/sim/condition.hpp"
#include "fuzzypid/sim/experiment.hpp"
#include "fuzzypid/sim/random.hpp"

namespace fuzzypid::sim {

// The reference of one tick and how long the plant then advances.
struct PathSample {
  double t_s = 0.0;                  // time of the sample (the condition's pulses follow it), s
  robot::JointVector theta_d{};      // reference angle, rad
  robot::JointVector theta_d_dot{};  // reference velocity, rad/s
  double dt_s = 0.0;                 // to the next sample: the plant's step, s
};

// What one tick injects between path, controller and plant (fault-injection and soak tests). Every
// field's default leaves the tick as it is; a zero offset leaves its value untouched bit for bit
// (even a -0.0, which adding +0.0 would turn into +0.0).
struct TickInjection {
  // Added to the reference angle the controller is given (a setpoint jump; the reference velocity
  // is kept). TickResult::theta_d includes it.
  robot::JointVector reference_offset_rad{};
  // Sensor faults, per joint. Added to the measured angle or velocity after the condition's noise
  // (a bias; NaN or +/-inf make the reading NaN or +/-inf) ...
  robot::JointVector measured_position_offset_rad{};
  robot::JointVector measured_velocity_offset_rad_s{};
  // ... or, where set, the reading the controller gets instead (a stuck sensor, a corrupted
  // reading such as NaN, +/-inf or 1e300); the offset is then not applied.
  std::array<std::optional<double>, robot::kNumJoints> measured_position_rad{};
  std::array<std::optional<double>, robot::kNumJoints> measured_velocity_rad_s{};
  // The dt the controller is given, when its clock says other than ClosedLoop::tick_s() (jitter,
  // or a bad dt: 0, negative, NaN, inf).
  std::optional<double> controller_dt_s;
  // The time the plant advances, when it is not the sample's dt_s (a late or early tick).
  std::optional<double> plant_dt_s;
  // Joint torque held over the plant step on top of the condition's contact disturbance, N·m.
  robot::JointVector disturbance_torque_nm{};
};

struct TickResult {
  double t_s = 0.0;                  // time of the sample
  robot::JointVector theta_d{};      // reference angle given to the controller, rad
  robot::JointVector theta_d_dot{};  // reference velocity, rad/s
  robot::JointVector theta{};        // true angle at the sample (before the plant step), rad
  robot::JointVector theta_dot{};    // true velocity at the sample, rad/s
  controller::Command command{};     // the controller's output and statuses
  robot::JointVector torque_nm{};    // the torque asked of the plant
  robot::PlantStatus plant = robot::PlantStatus::Ok;  // of the step (Ok when not advanced)
};

class ClosedLoop {
 public:
  // The plant of `condition` at the start of its path (at rest, initial error applied), the
  // controller of `controller` with output limits matching the plant's torque limits.
  [[nodiscard]] static std::optional<ClosedLoop> create(const Experiment& experiment,
                                                        const Condition& condition,
                                                        const ControllerSpec& controller,
                                                        std::string& error);
  // The same with a controller built by the caller (e.g. JointControllers::create with one
  // configuration per joint). Its output limits should be experiment.output_limit(condition,
  // units) so that the controller knows when the plant saturates.
  [[nodiscard]] static std::optional<ClosedLoop> create(const Experiment& experiment,
                                                        const Condition& condition,
                                                        controller::JointControllers controller,
                                                        std::string& error);

  // One tick at path sample k (k < samples()); `advance` = false skips the plant step (the last
  // sample of a run has nothing after it).
  TickResult tick(std::size_t k, bool advance = true) noexcept;
  // One tick following `sample` with `injection` applied.
  TickResult tick(const PathSample& sample, const TickInjection& injection = {},
                  bool advance = true) noexcept;

  // Sample k of the path (k < samples()); dt_s is the path's own interval to sample k + 1 (equal
  // to the tick to 1e-12, checked by Experiment::create), tick_s() after the last sample.
  PathSample sample(std::size_t k) const noexcept;
  // Tick n of the path played back and forth without end (A -> B -> A -> ..., 2 (samples() - 1)
  // ticks a cycle): forwards samples 0 .. samples() - 2, then backwards samples() - 1 .. 1 with
  // the velocities negated. t_s keeps running (n ticks after the start; sample(n)'s time on the
  // first leg). A path of one sample holds it.
  PathSample cyclic_sample(std::uint64_t n) const noexcept;

  // Puts the plant at `position_rad`, `velocity_rad_s` (the controller keeps its state).
  void reset_plant(const robot::JointVector& position_rad,
                   const robot::JointVector& velocity_rad_s) noexcept;

  std::size_t samples() const noexcept { return path_->time_s.size(); }
  double tick_s() const noexcept { return tick_s_; }
  const controller::JointControllers& controller() const noexcept { return *controller_; }
  const robot::JointPlant& plant() const noexcept { return plant_; }
  const robot::JointPathResult& path() const noexcept { return *path_; }

 private:
  ClosedLoop(const Experiment& experiment, const Condition& condition,
             const robot::JointPathResult& path, controller::JointControllers controller);
  // The loop of a condition the experiment has not refused (both create()s check that first).
  [[nodiscard]] static std::optional<ClosedLoop> assemble(const Experiment& experiment,
                                                          const Condition& condition,
                                                          controller::JointControllers controller,
                                                          std::string& error);

  const Experiment* experiment_;
  const robot::JointPathResult* path_;
  std::array<bool, robot::kNumJoints> continuous_{};
  // The nominal model for the gravity feed-forward (a copy: a model's queries are not
  // thread-safe, and loops of one experiment run on several threads).
  std::optional<robot::RobotModel> feedforward_model_;
  Condition condition_;
  PulseTrain pulses_;
  robot::JointPlant plant_;
  std::optional<controller::JointControllers> controller_;
  GainUnits units_;
  double tick_s_;
  Random noise_;
};

}  // namespace fuzzypid::sim
