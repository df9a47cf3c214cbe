// Internal: fixed-size rigid-body dynamics of the six-joint chain (Featherstone's recursive
// Newton-Euler and composite-rigid-body algorithms), over parameters extracted once from the KDL
// chain. Included by src/robot/*.cpp and by the robot tests that check it against KDL's
// ChainDynParam; this header names no KDL type, so those tests need no KDL headers.
//
// Conventions (those of KDL, which the parameters come from):
// - body i is the link moved by the chain's i-th moving joint, with the fixed segments that follow
//   it merged in; its frame is the tip frame of the segment that carries joint i;
// - gravity points along -z of the chain's root frame;
// - torques are those of KDL's ChainDynParam: M(q) q̈ + C(q, q̇) q̇ + g(q).
// Every member is noexcept and allocation-free; the object is immutable after construction, so one
// instance can be shared by any number of threads.
#pragma once

#include <array>

#include <Eigen/Core>

#include "fuzzypid/robot/robot_model.hpp"
#include "fuzzypid/robot/types.hpp"

namespace KDL {
class Chain;
}

namespace fuzzypid::robot::detail {

class RigidBodyDynamics {
 public:
  using Vec3 = Eigen::Vector3d;
  using Mat3 = Eigen::Matrix3d;
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  using Mat6 = Eigen::Matrix<double, 6, 6>;

  // One moving body. Its frame is the tip frame of the segment carrying its joint, turned so that
  // the joint axis is the frame's z axis (the turn is the identity when the URDF axis is already
  // z). rotation0 and position0 place it in its parent body's frame (the root's for body 0) at
  // q_i = 0: x_parent = rotation0 · Rz(q_i) · x + position0. The inertia is the body's with its
  // fixed successors merged in: mass m (kg), first moment h = m·c (kg·m, c the center of mass) and
  // rotational inertia about the frame origin (kg·m²), in the body frame.
  struct Body {
    Mat3 rotation0 = Mat3::Identity();
    Vec3 position0 = Vec3::Zero();
    double mass = 0.0;
    Vec3 first_moment = Vec3::Zero();
    Mat3 rotational_inertia = Mat3::Zero();
  };

  RigidBodyDynamics() = default;
  // The chain must have kNumJoints rotational joints whose axes pass through the origin of their
  // segment's tip frame, with no joint offset or scale: RobotModel::load() builds such chains from
  // URDF (a URDF joint's axis passes through its child link's origin).
  explicit RigidBodyDynamics(const KDL::Chain& chain);

  // M(q) (kg·m², links only) and the bias torque C(q, q̇) q̇ + g(q) (N·m) for gravity of magnitude
  // gravity_m_s2 (0 = none), sharing one kinematic pass.
  void mass_and_bias(const Vec6& q, const Vec6& qd, double gravity_m_s2, Mat6& mass,
                     Vec6& bias) const noexcept;

  // C(q, q̇) q̇ + g(q) alone: one recursive Newton-Euler pass with q̈ = 0.
  [[nodiscard]] Vec6 bias(const Vec6& q, const Vec6& qd, double gravity_m_s2) const noexcept;

  // M(q) alone (composite-rigid-body algorithm).
  [[nodiscard]] Mat6 mass_matrix(const Vec6& q) const noexcept;

  const std::array<Body, kNumJoints>& bodies() const noexcept { return bodies_; }

 private:
  std::array<Body, kNumJoints> bodies_{};
};

// The dynamics extracted from the model's chain when it was loaded (or copied, or given a payload).
[[nodiscard]] const RigidBodyDynamics& dynamics_of(const RobotModel& model) noexcept;

// KDL's ChainDynParam::JntToGravity on the model's chain: the independent reference the tests
// check RobotModel::gravity_torque (this RNEA) against. NaN with a RobotData of another model.
[[nodiscard]] JointVector kdl_gravity_torque(const RobotModel& model, const JointVector& q,
                                             double gravity_m_s2, RobotData& data) noexcept;

}  // namespace fuzzypid::robot::detail
