// N independent joint controllers (6 for the ER50-C20) stepped together once per tick.
#pragma once

#include <array>
#include <cstddef>
#include <utility>

#include "fuzzypid/control/fuzzy_pid.hpp"
#include "fuzzypid/pid/pid.hpp"
#include "fuzzypid/scalar.hpp"
#include "fuzzypid/status.hpp"

namespace fuzzypid::control {

template <class Scalar, std::size_t N>
using JointVector = std::array<Scalar, N>;

// The commands of one tick. A joint whose input is faulty holds its previous command and reports
// the fault in joint_status; the other joints are controlled normally. `status` is the worst of
// the per-joint statuses.
template <class Scalar, std::size_t N>
struct JointCommand {
  JointVector<Scalar, N> command{};  // e.g. joint torques, N·m
  std::array<Status, N> joint_status{};
  Status status = Status::Ok;
};

// Controller is pid::Pid<Scalar> or FuzzyPid<Scalar, System> (anything with
// `Status update(const pid::Input<Scalar>&, Scalar)` and `Scalar output()`).
template <class Scalar, std::size_t N, class Controller = FuzzyPid<Scalar>>
class JointController {
  FUZZYPID_ASSERT_SCALAR(Scalar);
  static_assert(N >= 1, "a joint controller needs at least one joint");

 public:
  using Vector = JointVector<Scalar, N>;
  using Command = JointCommand<Scalar, N>;

  JointController() = default;
  // Every joint starts as a copy of `prototype`. Copy-constructed, so Controller need not be
  // default-constructible (FuzzyPid with a custom System is not).
  explicit JointController(const Controller& prototype) noexcept
      : joints_(fill(prototype, std::make_index_sequence<N>{})) {}
  explicit JointController(const std::array<Controller, N>& joints) noexcept : joints_(joints) {}

  // One tick for all joints. Positions in rad, velocities in rad/s, dt in s; the optional
  // feed-forward is added to each joint's output.
  Command step(const Vector& desired_position, const Vector& desired_velocity,
               const Vector& measured_position, const Vector& measured_velocity, Scalar dt_s,
               const Vector* feed_forward = nullptr) noexcept {
    Command out;
    for (std::size_t i = 0; i < N; ++i) {
      pid::Input<Scalar> in;
      in.setpoint = desired_position[i];
      in.measurement = measured_position[i];
      in.setpoint_rate = desired_velocity[i];
      in.measurement_rate = measured_velocity[i];
      in.feed_forward = feed_forward != nullptr ? (*feed_forward)[i] : Scalar(0);
      const Status s = joints_[i].update(in, dt_s);
      out.joint_status[i] = s;
      out.status = worst(out.status, s);
      out.command[i] = joints_[i].output();
    }
    return out;
  }

  void reset() noexcept {
    for (auto& j : joints_)
      j.reset();
  }

  static constexpr std::size_t size() noexcept { return N; }
  Controller& joint(std::size_t i) noexcept { return joints_[i]; }
  const Controller& joint(std::size_t i) const noexcept { return joints_[i]; }

 private:
  template <std::size_t... I>
  static std::array<Controller, N> fill(const Controller& prototype,
                                        std::index_sequence<I...>) noexcept {
    return {{(static_cast<void>(I), prototype)...}};
  }

  std::array<Controller, N> joints_{};
};

}  // namespace fuzzypid::control
