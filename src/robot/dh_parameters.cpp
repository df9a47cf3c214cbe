// Closed-form forward kinematics of the Table 1 modified D-H model.
#include "fuzzypid/robot/dh_parameters.hpp"

#include <cmath>

namespace fuzzypid::robot {
namespace {

// Rotation about x by a twist of 0 or ±90° written with exact entries.
Eigen::Matrix3d rot_x_quarter(int quarter_turns) noexcept {
  const double s = quarter_turns == 0 ? 0.0 : (quarter_turns > 0 ? 1.0 : -1.0);
  const double c = quarter_turns == 0 ? 1.0 : 0.0;
  Eigen::Matrix3d r;
  r << 1, 0, 0, 0, c, -s, 0, s, c;
  return r;
}

Eigen::Matrix3d rot_z(double q) noexcept {
  const double c = std::cos(q);
  const double s = std::sin(q);
  Eigen::Matrix3d r;
  r << c, -s, 0, s, c, 0, 0, 0, 1;
  return r;
}

// Table 1 twists alpha_{i-1} in quarter turns: 0, -90, 0, -90, 90, -90 deg.
constexpr int kTwist[kNumJoints] = {0, -1, 0, -1, 1, -1};

}  // namespace

Pose dh_forward_kinematics(const DhParameters& dh, const JointVector& q) noexcept {
  const double a[kNumJoints] = {0.0, dh.a1_m, dh.a2_m, dh.a3_m, 0.0, 0.0};
  const double d[kNumJoints] = {dh.d1_m, 0.0, 0.0, dh.d4_m, 0.0, 0.0};
  Pose pose;
  for (std::size_t i = 0; i < kNumJoints; ++i) {
    // T_{i-1,i} = RotX(alpha) TransX(a) RotZ(q) TransZ(d) = [Rx Rz, (a, 0, 0) + Rx (0, 0, d)].
    const Eigen::Matrix3d rx = rot_x_quarter(kTwist[i]);
    const Eigen::Vector3d offset =
        Eigen::Vector3d(a[i], 0.0, 0.0) + rx * Eigen::Vector3d(0, 0, d[i]);
    pose.position_m += pose.rotation * offset;
    pose.rotation = pose.rotation * rx * rot_z(q[i]);
  }
  return pose;
}

Eigen::Matrix3d dh_rotation_0_3(const JointVector& q) noexcept {
  return rot_z(q[0]) * rot_x_quarter(-1) * rot_z(q[1]) * rot_z(q[2]);
}

}  // namespace fuzzypid::robot
