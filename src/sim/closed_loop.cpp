#include "fuzzypid/sim/closed_loop.hpp"

#include <cmath>
#include <optional>
#include <utility>
#include <vector>

namespace fuzzypid::sim {

namespace {

// x + offset, but x itself when the offset is zero: x + 0.0 would turn a -0.0 into +0.0, and a
// default injection must leave every value as the plain tick has it.
double shifted(double x, double offset) noexcept {
  return offset == 0.0 ? x : x + offset;
}

// A measurement as the controller gets it: the reading (true value plus noise) with the injected
// offset, or the injected reading instead.
double reading(double measured, double offset, const std::optional<double>& replaced) noexcept {
  return replaced ? *replaced : shifted(measured, offset);
}

// x moved by a multiple of 2 pi into (-pi, pi].
double wrapped(double x) noexcept {
  constexpr double kPi = 3.14159265358979323846;
  const double w = std::remainder(x, 2.0 * kPi);
  return w <= -kPi ? w + 2.0 * kPi : w;
}

}  // namespace

std::optional<ClosedLoop> ClosedLoop::create(const Experiment& experiment,
                                             const Condition& condition,
                                             const ControllerSpec& controller, std::string& error) {
  if (std::string bad = experiment.refusal(condition); !bad.empty()) {
    error = "condition " + condition.name + ": " + bad;
    return std::nullopt;
  }
  auto joints = controller::JointControllers::create(
      controller, experiment.output_limit(condition, controller.units.gains), error);
  if (!joints) return std::nullopt;
  return assemble(experiment, condition, std::move(*joints), error);
}

std::optional<ClosedLoop> ClosedLoop::create(const Experiment& experiment,
                                             const Condition& condition,
                                             controller::JointControllers controller,
                                             std::string& error) {
  if (std::string bad = experiment.refusal(condition); !bad.empty()) {
    error = "condition " + condition.name + ": " + bad;
    return std::nullopt;
  }
  return assemble(experiment, condition, std::move(controller), error);
}

std::optional<ClosedLoop> ClosedLoop::assemble(const Experiment& experiment,
                                               const Condition& condition,
                                               controller::JointControllers controller,
                                               std::string& error) {
  const robot::JointPathResult* path = experiment.path(condition, error);
  if (path == nullptr) return std::nullopt;
  ClosedLoop loop(experiment, condition, *path, std::move(controller));
  if (!loop.plant_.valid()) {
    error = "invalid plant configuration for condition " + condition.name;
    return std::nullopt;
  }
  return loop;
}

ClosedLoop::ClosedLoop(const Experiment& experiment, const Condition& condition,
                       const robot::JointPathResult& path, controller::JointControllers controller)
    : experiment_(&experiment),
      path_(&path),
      condition_(condition),
      pulses_(condition.pulses()),
      plant_(experiment.plant_model(condition), experiment.plant_config(condition)),
      controller_(std::move(controller)),
      units_(controller_->spec().units.gains),
      tick_s_(experiment.options().tick_s),
      noise_(condition.seed) {
  plant_.reset(experiment.initial_position(path, condition), robot::JointVector{});
  for (std::size_t i = 0; i < robot::kNumJoints; ++i)
    continuous_[i] = std::isinf(experiment.model().lower_limits_rad()[i]) &&
                     std::isinf(experiment.model().upper_limits_rad()[i]);
  if (controller_->spec().feedforward.gravity) feedforward_model_.emplace(experiment.model());
}

PathSample ClosedLoop::sample(std::size_t k) const noexcept {
  PathSample s;
  s.t_s = path_->time_s[k];
  s.theta_d = path_->position_rad[k];
  s.theta_d_dot = path_->velocity_rad_s[k];
  // The path's own sample interval (equal to the tick to 1e-12, checked by Experiment::create).
  const std::size_t n = path_->time_s.size();
  s.dt_s = k + 1 < n ? path_->time_s[k + 1] - s.t_s : tick_s_;
  return s;
}

PathSample ClosedLoop::cyclic_sample(std::uint64_t n) const noexcept {
  const std::vector<double>& time = path_->time_s;
  const std::size_t count = time.size();
  if (count < 2) {
    PathSample s = sample(0);
    s.t_s = time.front() + static_cast<double>(n) * tick_s_;
    return s;
  }
  const std::uint64_t legs = count - 1;  // ticks of one leg
  const std::uint64_t cycle = n / (2 * legs);
  const std::uint64_t phase = n % (2 * legs);
  const double leg_s = time.back() - time.front();
  if (phase < legs) {
    const auto k = static_cast<std::size_t>(phase);
    PathSample s = sample(k);
    s.t_s = time.front() + (static_cast<double>(cycle) * 2.0 * leg_s + (time[k] - time.front()));
    return s;
  }
  // Backwards: from the last sample down to sample 1, each step as long as the forward one.
  const auto k = static_cast<std::size_t>(2 * legs - phase);
  PathSample s;
  s.t_s =
      time.front() + (static_cast<double>(cycle) * 2.0 * leg_s + leg_s + (time.back() - time[k]));
  s.theta_d = path_->position_rad[k];
  s.theta_d_dot = path_->velocity_rad_s[k];
  for (double& v : s.theta_d_dot)
    v = -v;
  s.dt_s = time[k] - time[k - 1];
  return s;
}

void ClosedLoop::reset_plant(const robot::JointVector& position_rad,
                             const robot::JointVector& velocity_rad_s) noexcept {
  plant_.reset(position_rad, velocity_rad_s);
}

TickResult ClosedLoop::tick(std::size_t k, bool advance) noexcept {
  return tick(sample(k), TickInjection{}, advance);
}

TickResult ClosedLoop::tick(const PathSample& sample, const TickInjection& injection,
                            bool advance) noexcept {
  TickResult r;
  r.t_s = sample.t_s;
  r.theta_d_dot = sample.theta_d_dot;
  r.theta = plant_.position();
  r.theta_dot = plant_.velocity();
  for (std::size_t i = 0; i < robot::kNumJoints; ++i)
    r.theta_d[i] = shifted(sample.theta_d[i], injection.reference_offset_rad[i]);
  controller::Input in;
  in.desired_position_rad = r.theta_d;
  in.desired_velocity_rad_s = r.theta_d_dot;
  // What the drive measures: the true state, or the encoder's reading (plant.hpp).
  in.measured_position_rad = plant_.measured_position();
  in.measured_velocity_rad_s = plant_.measured_velocity();
  for (std::size_t i = 0; i < robot::kNumJoints; ++i) {
    // The noise is drawn whatever is injected, so that the same seed gives the same noise.
    in.measured_position_rad[i] += noise_.normal(condition_.noise_position_rad);
    in.measured_velocity_rad_s[i] += noise_.normal(condition_.noise_velocity_rad_s);
    in.measured_position_rad[i] =
        reading(in.measured_position_rad[i], injection.measured_position_offset_rad[i],
                injection.measured_position_rad[i]);
    in.measured_velocity_rad_s[i] =
        reading(in.measured_velocity_rad_s[i], injection.measured_velocity_offset_rad_s[i],
                injection.measured_velocity_rad_s[i]);
    if (continuous_[i] && std::isfinite(in.measured_position_rad[i]) &&
        std::isfinite(r.theta_d[i])) {
      const double measured = in.measured_position_rad[i];
      r.theta_d[i] = measured + wrapped(r.theta_d[i] - measured);
      in.desired_position_rad[i] = r.theta_d[i];
    }
  }
  r.command = controller_->step(in, injection.controller_dt_s.value_or(tick_s_));
  r.torque_nm = experiment_->torque_from_command(r.command.output, units_);
  if (feedforward_model_) {
    const robot::JointVector g = feedforward_model_->gravity_torque(sample.theta_d);
    for (std::size_t i = 0; i < robot::kNumJoints; ++i)
      r.torque_nm[i] += g[i];
  }
  if (!advance) return r;
  robot::JointVector disturbance{};
  const double a = pulses_.at(r.t_s);
  for (std::size_t i = 0; i < robot::kNumJoints; ++i)
    disturbance[i] =
        shifted(a * experiment_->nominal_inertia()[i], injection.disturbance_torque_nm[i]);
  r.plant = plant_.step(r.torque_nm, injection.plant_dt_s.value_or(sample.dt_s), disturbance);
  return r;
}

}  // namespace fuzzypid::sim
