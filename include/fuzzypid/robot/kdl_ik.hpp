// Numerical inverse kinematics through Orocos KDL, for comparison with the closed form and for
// URDFs the closed form does not cover.
//
//  - Newton-Raphson with joint limits (KDL ChainIkSolverPos_NR_JL, pseudo-inverse velocity solver):
//    iterates are clamped into the limits; converged when every twist component of the pose error
//    is below `tolerance`.
//  - Levenberg-Marquardt (KDL ChainIkSolverPos_LMA) with the error weights L. KDL's default weights
//    orientation at 0.01 and so accepts large orientation errors; here position (m) and rotation
//    (rad) weigh 1 by default. LMA ignores joint limits: its result is wrapped by 2 pi towards the
//    seed where that fits, then rejected with JointLimits if it still lies outside.
//
// Both results are checked by forward kinematics: a solution whose position error exceeds
// `tolerance` m or whose rotation error exceeds `tolerance` rad is reported as NoConvergence.
// These calls may allocate (KDL's internals); use AnalyticIk in a real-time loop.
#pragma once

#include <array>
#include <cstdint>
#include <memory>

#include "fuzzypid/robot/ik_status.hpp"
#include "fuzzypid/robot/types.hpp"

namespace fuzzypid::robot {

class RobotModel;

enum class KdlIkMethod : std::uint8_t { NewtonRaphson, LevenbergMarquardt };

struct KdlIkOptions {
  double tolerance = 1e-6;  // pose error accepted, m and rad
  unsigned int max_iterations = 500;
  // LMA weights of the error twist (vx, vy, vz, wx, wy, wz), position in m and rotation in rad.
  std::array<double, 6> lma_weights = {1.0, 1.0, 1.0, 1.0, 1.0, 1.0};
};

class KdlIk {
 public:
  explicit KdlIk(const RobotModel& model, const KdlIkOptions& options = {});
  KdlIk(const KdlIk& other);
  KdlIk(KdlIk&& other) noexcept;
  KdlIk& operator=(const KdlIk& other);
  KdlIk& operator=(KdlIk&& other) noexcept;
  ~KdlIk();

  // `out` is written only when the status is Ok.
  [[nodiscard]] IkStatus solve(KdlIkMethod method, const Pose& target, const JointVector& seed,
                               JointVector& out) const noexcept;

  const KdlIkOptions& options() const noexcept;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fuzzypid::robot
