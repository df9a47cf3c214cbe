// Helpers shared by the robot tests: the bundled model, seeded random joint vectors, pose errors.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "fuzzypid/robot/robot_data.hpp"
#include "fuzzypid/robot/robot_model.hpp"
#include "fuzzypid_support/uniform_real.hpp"

namespace fuzzypid::robot::test {

inline const RobotModel& bundled_model() {
  static const RobotModel model = [] {
    LoadResult r = RobotModel::load(default_urdf_path());
    if (!r.model) {
      std::fprintf(stderr, "cannot load the bundled URDF: %s\n", r.error.c_str());
      std::abort();
    }
    return *r.model;
  }();
  return model;
}

// A generator whose seed is printed, so a failing property test can be replayed.
inline std::mt19937_64 seeded_rng(std::uint64_t seed, const char* what) {
  std::printf("[ seed     ] %s: %llu\n", what, static_cast<unsigned long long>(seed));
  return std::mt19937_64(seed);
}

inline JointVector random_within(const RobotModel& m, std::mt19937_64& rng) {
  JointVector q{};
  for (std::size_t i = 0; i < kNumJoints; ++i) {
    fuzzypid::support::UniformReal<double> d(m.lower_limits_rad()[i], m.upper_limits_rad()[i]);
    q[i] = d(rng);
  }
  return q;
}

// One query each on a RobotData made for it: the tests' shorthand (it allocates; the control path
// keeps one RobotData and reuses it, tests/robot/test_no_allocation.cpp).
inline Pose fk(const RobotModel& m, const JointVector& q) {
  RobotData data(m);
  return m.forward_kinematics(q, data);
}
inline Eigen::Matrix<double, 6, 6> jacobian_of(const RobotModel& m, const JointVector& q) {
  RobotData data(m);
  return m.jacobian(q, data);
}
inline Eigen::Matrix<double, 6, 6> mass_matrix_of(const RobotModel& m, const JointVector& q) {
  RobotData data(m);
  return m.mass_matrix(q, data);
}
inline JointVector inertia_diagonal_of(const RobotModel& m, const JointVector& q) {
  RobotData data(m);
  return m.inertia_diagonal(q, data);
}
inline JointVector coriolis_of(const RobotModel& m, const JointVector& q, const JointVector& qd) {
  RobotData data(m);
  return m.coriolis_torque(q, qd, data);
}

inline double position_error(const Pose& a, const Pose& b) {
  return (a.position_m - b.position_m).norm();
}

// Angle (rad) of the rotation taking a to b.
inline double rotation_error(const Pose& a, const Pose& b) {
  return Eigen::AngleAxisd(a.rotation.transpose() * b.rotation).angle();
}

}  // namespace fuzzypid::robot::test
