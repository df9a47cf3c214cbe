// The ER50-C20 geometry as modified (Craig) Denavit-Hartenberg parameters, Table 1 and section 2.2:
//
//   i | alpha_{i-1} | a_{i-1} | d_i | theta_i
//   1 |      0      |    0    | d1  |  q1
//   2 |    -90°     |   a1    |  0  |  q2
//   3 |      0      |   a2    |  0  |  q3
//   4 |    -90°     |   a3    | d4  |  q4
//   5 |     90°     |    0    |  0  |  q5
//   6 |    -90°     |    0    |  0  |  q6
//
// with T_{i-1,i} = RotX(alpha_{i-1}) TransX(a_{i-1}) RotZ(theta_i) TransZ(d_i). Axes 4, 5 and 6
// meet at the origin of frames 4-6 (a spherical wrist), so the tip position depends on q1..q3 only.
#pragma once

#include "fuzzypid/robot/types.hpp"

namespace fuzzypid::robot {

struct DhParameters {
  double a1_m = 0.220;  // Section 2.2
  double a2_m = 0.900;
  double a3_m = 0.160;
  double d1_m = 0.563;
  double d4_m = 1.014;
};

// Table 1 as written; the twists are fixed by the structure above.
[[nodiscard]] constexpr DhParameters er50_c20_dh() noexcept {
  return DhParameters{};
}

// Closed-form forward kinematics of the table above (no KDL): pose of frame 6 in frame 0.
[[nodiscard]] Pose dh_forward_kinematics(const DhParameters& dh, const JointVector& q) noexcept;

// Rotation of frame 3 in frame 0, the part of the arm the wrist sits on.
[[nodiscard]] Eigen::Matrix3d dh_rotation_0_3(const JointVector& q) noexcept;

}  // namespace fuzzypid::robot
