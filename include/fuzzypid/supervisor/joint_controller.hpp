// N independent joint controllers (6 for the ER50-C20) stepped together once per tick.
#pragma once

#include <array>
#include <cstddef>
#include <utility>

#include "fuzzypid/pid/pid.hpp"
#include "fuzzypid/scalar.hpp"
#include "fuzzypid/status.hpp"

namespace fuzzypid::supervisor {

template <class Scalar, std::size_t N>
using JointVector = std::array<Scalar, N>;

// One tick's references and measurements, per joint.
template <class Scalar, std::size_t N>
struct JointInput {
  JointVector<Scalar, N> desired_position_rad{};
  JointVector<Scalar, N> desired_velocity_rad_s{};
  JointVector<Scalar, N> measured_position_rad{};
  JointVector<Scalar, N> measured_velocity_rad_s{};
  // Added to each joint's output, in the output's units (N·m, or rad/s² with gains normalised by
  // inertia).
  JointVector<Scalar, N> feed_forward{};
};

// The commands of one tick. A joint whose input is faulty holds its previous command and reports
// the fault in joint_status; the other joints are controlled normally. `status` is the worst of
// the per-joint statuses.
template <class Scalar, std::size_t N>
struct JointOutput {
  // The controllers' outputs u: joint torques, N·m, with gains in N·m/rad, or accelerations,
  // rad/s², with gains normalised by inertia (controller files' acceleration units; the caller
  // applies J^_i u_i). No unit in the name because it is the gains' choice.
  JointVector<Scalar, N> output{};
  std::array<Status, N> joint_status{};
  Status status = Status::Ok;
};

// Controller is pid::Pid<Scalar> or FuzzyPid<Scalar, Supervisor> (anything with
// `Status update(const pid::Input<Scalar>&, Scalar)` and `Scalar output()`); paper.hpp has the
// paper's as paper::JointController. The controllers hold per-joint state only: a fuzzy
// supervisor is shared, not copied.
template <class Scalar, std::size_t N, class Controller>
class JointController {
  FUZZYPID_ASSERT_SCALAR(Scalar);
  static_assert(N >= 1, "a joint controller needs at least one joint");

 public:
  using Vector = JointVector<Scalar, N>;
  using Input = JointInput<Scalar, N>;
  using Output = JointOutput<Scalar, N>;

  JointController() = default;
  // Every joint starts as a copy of `prototype`. Copy-constructed, so Controller need not be
  // default-constructible.
  explicit JointController(const Controller& prototype)
      : joints_(fill(prototype, std::make_index_sequence<N>{})) {}
  explicit JointController(const std::array<Controller, N>& joints) : joints_(joints) {}

  // One tick for all joints over dt_s seconds.
  [[gnu::flatten]] [[nodiscard]] Output step(const Input& in, Scalar dt_s) noexcept {
    // Filled joint by joint and assembled at the end (no zero-fill of the result first).
    JointVector<Scalar, N> torque;
    std::array<Status, N> joint_status;
    Status status = Status::Ok;
    for (std::size_t i = 0; i < N; ++i) {
      pid::Input<Scalar> joint;
      joint.setpoint = in.desired_position_rad[i];
      joint.measurement = in.measured_position_rad[i];
      joint.setpoint_rate = in.desired_velocity_rad_s[i];
      joint.measurement_rate = in.measured_velocity_rad_s[i];
      joint.feed_forward = in.feed_forward[i];
      const Status s = joints_[i].update(joint, dt_s);
      joint_status[i] = s;
      status = worst(status, s);
      torque[i] = joints_[i].output();
    }
    return {torque, joint_status, status};
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
  static std::array<Controller, N> fill(const Controller& prototype, std::index_sequence<I...>) {
    return {{(static_cast<void>(I), prototype)...}};
  }

  std::array<Controller, N> joints_{};
};

}  // namespace fuzzypid::supervisor
