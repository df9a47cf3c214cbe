// The section 6 experiment's Cartesian path: a straight line from A to B sampled at a fixed count,
// turned into a joint-space reference by inverse kinematics seeded with the previous sample.
//
// Section 6 gives A = (1350, 530, 1250) mm, B = (1615, 240, 490) mm, 101 samples over 5 s (one per
// 0.05 s) and start/end joint vectors. Under Table 1 those joint vectors do not reach A and B
// (docs/robot.md quotes the distances), so the reference is planned from A and B alone, with an
// orientation chosen here.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fuzzypid/robot/ik.hpp"
#include "fuzzypid/robot/ik_status.hpp"
#include "fuzzypid/robot/types.hpp"

namespace fuzzypid::robot {

class RobotModel;

// Section 6 start and end joint vectors θ and θ' (rad), as printed.
inline constexpr JointVector kPaperStartJoints = {0.176, -0.701, 0.079, -0.0002, -0.949, -1.019};
inline constexpr JointVector kPaperEndJoints = {-0.236, -0.166, -0.691, 0.0, -0.715, -0.237};

enum class OrientationMode : std::uint8_t {
  Fixed,  // start_rotation at every sample
  Slerp,  // spherical linear interpolation from start_rotation to end_rotation
};

struct CartesianPathSpec {
  Eigen::Vector3d start_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d end_m = Eigen::Vector3d::Zero();
  Eigen::Matrix3d start_rotation = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d end_rotation = Eigen::Matrix3d::Identity();  // used by Slerp only
  OrientationMode orientation = OrientationMode::Fixed;
  std::size_t samples = 101;  // section 6; at least 2
  double duration_s = 5.0;    // section 6
  // Largest change of any joint between consecutive samples before the path is declared to jump
  // branches. A 5 s, 1 m line moves no joint more than a few hundredths of a radian per sample.
  double max_joint_step_rad = 0.25;
};

// The fixed tool orientation used for the section 6 path (see docs/robot.md for the choice).
[[nodiscard]] Eigen::Matrix3d paper_path_rotation();

// A and B of section 6 converted from mm to m, orientation fixed at paper_path_rotation(),
// 101 samples over 5 s.
[[nodiscard]] CartesianPathSpec paper_path_spec();

enum class PathStatus : std::uint8_t {
  Ok,
  InvalidSpec,  // fewer than 2 samples, non-positive duration, non-finite or improper rotation
  IkFailed,     // a sample has no solution (see ik_status)
  JointJump,    // consecutive samples differ by more than max_joint_step_rad in some joint
};

[[nodiscard]] constexpr const char* to_string(PathStatus s) noexcept {
  switch (s) {
    case PathStatus::Ok:
      return "ok";
    case PathStatus::InvalidSpec:
      return "invalid_spec";
    case PathStatus::IkFailed:
      return "ik_failed";
    case PathStatus::JointJump:
      return "joint_jump";
  }
  return "unknown";
}

struct JointPathResult {
  PathStatus status = PathStatus::InvalidSpec;
  IkStatus ik_status = IkStatus::Ok;  // of the first failing sample when status is IkFailed
  std::size_t first_failure = std::numeric_limits<std::size_t>::max();  // sample index
  std::string message;                                                  // empty when Ok

  std::vector<double> time_s;               // t_k = k * duration / (samples - 1)
  std::vector<Pose> poses;                  // the Cartesian targets
  std::vector<JointVector> position_rad;    // IK of each target (filled up to the failure)
  std::vector<JointVector> velocity_rad_s;  // central differences, one-sided at the ends
  JointVector max_speed_rad_s{};            // largest |velocity| of each joint over the path
  bool within_velocity_limits = false;      // max_speed within the model's velocity limits

  bool ok() const noexcept { return status == PathStatus::Ok; }
};

// Samples the line start_m -> end_m uniformly in time, solves IK for each sample seeded with the
// previous solution (the first with `seed`), and differentiates. Samples are computed only up to
// the first failure.
[[nodiscard]] JointPathResult plan_joint_path(const RobotModel& model,
                                              const CartesianPathSpec& spec, IkSolver solver,
                                              const JointVector& seed);

// Same, reusing an existing solver set (avoids rebuilding the KDL solvers).
[[nodiscard]] JointPathResult plan_joint_path(const InverseKinematics& ik, const RobotModel& model,
                                              const CartesianPathSpec& spec, IkSolver solver,
                                              const JointVector& seed);

}  // namespace fuzzypid::robot
