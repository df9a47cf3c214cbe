// Basic robot-model vocabulary shared by every header of the robot part: the joint vector of the
// six-axis arm and the tip pose. SI units throughout (m, rad).
#pragma once

#include <array>
#include <cstddef>

#include <Eigen/Core>

namespace fuzzypid::robot {

// The ER50-C20 has six revolute joints (Table 1).
constexpr std::size_t kNumJoints = 6;

// Joint angles (rad), velocities (rad/s) or torques (N·m), ordered J1..J6.
using JointVector = std::array<double, kNumJoints>;

// Pose of the chain tip (D-H frame 6 for the bundled URDF) in the chain root (D-H frame 0).
struct Pose {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // columns: tip axes in the root frame
};

}  // namespace fuzzypid::robot
