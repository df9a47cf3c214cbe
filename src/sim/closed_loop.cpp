#include "fuzzypid/sim/closed_loop.hpp"

#include <utility>

namespace fuzzypid::sim {

std::optional<ClosedLoop> ClosedLoop::create(const Experiment& experiment,
                                             const Condition& condition,
                                             const ControllerSpec& controller, std::string& error) {
  if (std::string bad = condition.validate(); !bad.empty()) {
    error = "condition " + condition.name + ": " + bad;
    return std::nullopt;
  }
  const robot::JointPathResult* path = experiment.path(condition, error);
  if (path == nullptr) return std::nullopt;
  auto joints = controller_file::JointControllers::create(
      controller, experiment.output_limit(condition, controller.units.gains), error);
  if (!joints) return std::nullopt;
  ClosedLoop loop(experiment, condition, *path, std::move(*joints));
  if (!loop.plant_.valid()) {
    error = "invalid plant configuration for condition " + condition.name;
    return std::nullopt;
  }
  return loop;
}

ClosedLoop::ClosedLoop(const Experiment& experiment, const Condition& condition,
                       const robot::JointPathResult& path,
                       controller_file::JointControllers controller)
    : experiment_(&experiment),
      path_(&path),
      condition_(condition),
      pulses_(condition.pulses()),
      plant_(experiment.model(), experiment.plant_config(condition)),
      controller_(std::move(controller)),
      units_(controller_->spec().units.gains),
      tick_s_(experiment.options().tick_s),
      noise_(condition.seed) {
  plant_.reset(experiment.initial_position(path, condition), robot::JointVector{});
}

TickResult ClosedLoop::tick(std::size_t k, bool advance) noexcept {
  TickResult r;
  r.t_s = path_->time_s[k];
  r.theta_d = path_->position_rad[k];
  r.theta_d_dot = path_->velocity_rad_s[k];
  r.theta = plant_.position();
  r.theta_dot = plant_.velocity();
  controller_file::Input in;
  in.desired_position_rad = r.theta_d;
  in.desired_velocity_rad_s = r.theta_d_dot;
  in.measured_position_rad = r.theta;
  in.measured_velocity_rad_s = r.theta_dot;
  for (std::size_t i = 0; i < robot::kNumJoints; ++i) {
    in.measured_position_rad[i] += noise_.normal(condition_.noise_position_rad);
    in.measured_velocity_rad_s[i] += noise_.normal(condition_.noise_velocity_rad_s);
  }
  r.command = controller_->step(in, tick_s_);
  r.torque_nm = experiment_->torque_from_command(r.command.torque_nm, units_);
  if (!advance) return r;
  robot::JointVector disturbance{};
  const double a = pulses_.at(r.t_s);
  for (std::size_t i = 0; i < robot::kNumJoints; ++i)
    disturbance[i] = a * experiment_->nominal_inertia()[i];
  // The path's own sample interval (equal to the tick to 1e-12, checked by Experiment::create).
  const std::size_t n = path_->time_s.size();
  const double dt = k + 1 < n ? path_->time_s[k + 1] - r.t_s : tick_s_;
  r.plant = plant_.step(r.torque_nm, dt, disturbance);
  return r;
}

}  // namespace fuzzypid::sim
