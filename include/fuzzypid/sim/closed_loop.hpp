// One closed loop: the path, the six joints' controller, the torque and the plant, advanced one
// controller tick at a time. sim::Experiment::run, the real-time loop and the soak test all tick
// this one object, so they simulate the same thing.
//
// A tick k: sample k of the path (theta_d, theta_d dot) -> measured angles and velocities (true
// state plus the condition's Gaussian noise) -> controller -> torque (J^_i u_i with acceleration
// units) -> plant over one tick with the condition's contact disturbance held. create() allocates;
// tick() does not allocate, throw or print.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "fuzzypid/controller_file/joint_controllers.hpp"
#include "fuzzypid/robot/plant.hpp"
#include "fuzzypid/sim/condition.hpp"
#include "fuzzypid/sim/experiment.hpp"
#include "fuzzypid/sim/random.hpp"

namespace fuzzypid::sim {

struct TickResult {
  double t_s = 0.0;                    // time of the sample
  robot::JointVector theta_d{};        // reference angle, rad
  robot::JointVector theta_d_dot{};    // reference velocity, rad/s
  robot::JointVector theta{};          // true angle at the sample (before the plant step), rad
  robot::JointVector theta_dot{};      // true velocity at the sample, rad/s
  controller_file::Command command{};  // the controller's output and statuses
  robot::JointVector torque_nm{};      // the torque asked of the plant
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

  // One tick at path sample k (k < samples()); `advance` = false skips the plant step (the last
  // sample of a run has nothing after it).
  TickResult tick(std::size_t k, bool advance = true) noexcept;

  std::size_t samples() const noexcept { return path_->time_s.size(); }
  double tick_s() const noexcept { return tick_s_; }
  const controller_file::JointControllers& controller() const noexcept { return *controller_; }
  const robot::JointPlant& plant() const noexcept { return plant_; }
  const robot::JointPathResult& path() const noexcept { return *path_; }

 private:
  ClosedLoop(const Experiment& experiment, const Condition& condition,
             const robot::JointPathResult& path, controller_file::JointControllers controller);

  const Experiment* experiment_;
  const robot::JointPathResult* path_;
  Condition condition_;
  PulseTrain pulses_;
  robot::JointPlant plant_;
  std::optional<controller_file::JointControllers> controller_;
  GainUnits units_;
  double tick_s_;
  Random noise_;
};

}  // namespace fuzzypid::sim
