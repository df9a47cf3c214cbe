// Paths from files (robot/path_file.hpp): the CSV format, the interpolation at the tick, inverse
// kinematics of Cartesian rows on any arm, continuous joints, limits, and the reversed path.
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "fuzzypid/robot/ik.hpp"
#include "fuzzypid/robot/path_file.hpp"
#include "fuzzypid/robot/robot_model.hpp"
#include "test_support.hpp"

namespace fuzzypid::robot {
namespace {

using test::fk;

constexpr double kPi = 3.14159265358979323846;
const std::string kJoint = "t_s,q1_rad,q2_rad,q3_rad,q4_rad,q5_rad,q6_rad\n";
const std::string kPose = "t_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad\n";

const RobotModel& ur5() {
  static const RobotModel model = [] {
    LoadResult r = RobotModel::load(std::string(FUZZYPID_SOURCE_DIR) + "/urdf/ur5_class.urdf");
    if (!r.model) std::abort();
    return *r.model;
  }();
  return model;
}

std::string parse_error(const std::string& text) {
  PathTable t;
  std::string error;
  EXPECT_FALSE(parse_path_csv(text, "p.csv", t, error)) << text;
  return error;
}

TEST(PathFile, ReadsJointAndPoseHeadersWithCommentsAndSpaces) {
  PathTable t;
  std::string error;
  ASSERT_TRUE(parse_path_csv("# a comment\n" + kJoint + "0,1,2,3,4,5,6\n\n 0.5 , 1,2,3,4,5,7\n",
                             "p.csv", t, error))
      << error;
  EXPECT_EQ(t.kind, PathKind::Joint);
  ASSERT_EQ(t.time_s.size(), 2u);
  EXPECT_EQ(t.values[1][5], 7.0);
  EXPECT_EQ(t.line[1], 5u);
  ASSERT_TRUE(parse_path_csv(kPose + "0,1,2,3,0,0,0\n1,1,2,3,0,0,0", "p.csv", t, error)) << error;
  EXPECT_EQ(t.kind, PathKind::Cartesian);
}

TEST(PathFile, RefusesMalformedFilesNamingTheLine) {
  EXPECT_NE(parse_error("t,a,b\n0,1,2\n").find("p.csv:1: unknown header"), std::string::npos);
  EXPECT_NE(parse_error(kJoint + "0,0,0,0,0,0,0\n0,0,0,0,0,0,0\n")
                .find("p.csv:3: time 0 s does "
                      "not increase"),
            std::string::npos);
  EXPECT_NE(parse_error(kJoint + "0,0,0,0,0,0,0\n1,0,nan,0,0,0,0\n").find("p.csv:3: field 3"),
            std::string::npos);
  EXPECT_NE(parse_error(kJoint + "0,0,0,0,0,0,0\n1,0,inf,0,0,0,0\n").find("not finite"),
            std::string::npos);
  EXPECT_NE(parse_error(kJoint + "0,0,0,0,0,0,0\n").find("at least two rows, found 1"),
            std::string::npos);
  EXPECT_NE(parse_error(kJoint + "0,0,0,0,0,0\n1,0,0,0,0,0,0\n").find("expected 7 fields"),
            std::string::npos);
  EXPECT_NE(parse_error(kJoint + "0,0,0,0,0,0,0,0\n").find("more than 7 fields"),
            std::string::npos);
  EXPECT_NE(parse_error("").find("empty path file"), std::string::npos);
}

TEST(PathFile, RollPitchYawIsUrdfFixedAxis) {
  // R = Rz(yaw) Ry(pitch) Rx(roll): a pure yaw turns x towards y.
  const Eigen::Matrix3d r = rotation_from_rpy(0.0, 0.0, kPi / 2);
  EXPECT_NEAR(r(1, 0), 1.0, 1e-15);
  const Eigen::Matrix3d full = rotation_from_rpy(0.1, 0.2, 0.3);
  const Eigen::Matrix3d expected = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()) *
                                    Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()))
                                       .toRotationMatrix();
  EXPECT_LT((full - expected).norm(), 1e-15);
}

TEST(PathFile, InterpolationPassesThroughRowsAndItsVelocityIsItsDerivative) {
  // Rows every 0.1 s of a smooth curve, ticks every 0.01 s.
  std::string text = kJoint;
  for (int k = 0; k <= 20; ++k) {
    const double t = 0.1 * k;
    char row[256];
    std::snprintf(row, sizeof row, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", t,
                  0.3 * std::sin(t), -0.5 + 0.1 * t, 0.2 * std::cos(2 * t), 0.0, 0.1 * t * t, -0.2);
    text += row;
  }
  PathTable table;
  std::string error;
  ASSERT_TRUE(parse_path_csv(text, "curve.csv", table, error)) << error;
  const InverseKinematics ik(ur5());
  const JointPathResult p = joint_path_from_table(ik, ur5(), table, 0.01, JointVector{});
  ASSERT_TRUE(p.ok()) << p.message;
  ASSERT_EQ(p.time_s.size(), 201u);  // 2 s at 10 ms, both ends included
  for (std::size_t k = 0; k <= 20; ++k)
    for (std::size_t j = 0; j < kNumJoints; ++j)
      EXPECT_NEAR(p.position_rad[10 * k][j], table.values[k][j], 1e-12) << k << "," << j;
  // The velocity is the derivative of the interpolated angle (central difference of the ticks).
  for (std::size_t k = 1; k + 1 < p.time_s.size(); ++k)
    for (std::size_t j = 0; j < kNumJoints; ++j) {
      const double fd = (p.position_rad[k + 1][j] - p.position_rad[k - 1][j]) / 0.02;
      EXPECT_NEAR(p.velocity_rad_s[k][j], fd, 2e-3) << k << "," << j;
    }
  // A linear joint (q2 = -0.5 + 0.1 t) is reproduced exactly, angle and velocity.
  for (std::size_t k = 0; k < p.time_s.size(); ++k) {
    EXPECT_NEAR(p.position_rad[k][1], -0.5 + 0.1 * p.time_s[k], 1e-14);
    EXPECT_NEAR(p.velocity_rad_s[k][1], 0.1, 1e-12);
  }
}

TEST(PathFile, TheSlopeAtARowWeighsTheNearerNeighbourMoreOnUnevenRows) {
  // q1 = 0.1 t^2 at t = 0, 1, 3: the parabola through the three rows is q1 itself, so the slope
  // at t = 1 s is its derivative 0.2 rad/s (weights h1 / (h0 + h1) on the left difference 0.1,
  // h0 / (h0 + h1) on the right one 0.4; swapped they would give 0.3).
  PathTable table;
  std::string error;
  ASSERT_TRUE(parse_path_csv(kJoint + "0,0,-1,1,0,0,0\n1,0.1,-1,1,0,0,0\n3,0.9,-1,1,0,0,0\n",
                             "uneven.csv", table, error))
      << error;
  const InverseKinematics ik(ur5());
  const JointPathResult p = joint_path_from_table(ik, ur5(), table, 0.5, JointVector{});
  ASSERT_TRUE(p.ok()) << p.message;
  ASSERT_EQ(p.time_s.size(), 7u);
  EXPECT_EQ(p.time_s[2], 1.0);
  EXPECT_NEAR(p.position_rad[2][0], 0.1, 1e-15);
  EXPECT_NEAR(p.velocity_rad_s[2][0], 0.2, 1e-12);
}

TEST(PathFile, TheRunLastsThePathsDurationInWholeTicks) {
  PathTable table;
  std::string error;
  ASSERT_TRUE(
      parse_path_csv(kJoint + "1,0,-1,1,0,0,0\n1.234,0,-1,1,0,0,0.01\n", "p.csv", table, error));
  const InverseKinematics ik(ur5());
  const JointPathResult p = joint_path_from_table(ik, ur5(), table, 0.05, JointVector{});
  ASSERT_TRUE(p.ok()) << p.message;
  ASSERT_EQ(p.time_s.size(), 5u);  // 1.00, 1.05, ..., 1.20
  EXPECT_DOUBLE_EQ(p.time_s.front(), 1.0);
  EXPECT_NEAR(p.time_s.back(), 1.2, 1e-12);
}

// A path of less than one tick would be a one-sample run (ITAE 0): refused, with both durations.
// Exactly one tick is two samples and runs.
TEST(PathFile, RefusesAPathShorterThanOneTick) {
  PathTable table;
  std::string error;
  ASSERT_TRUE(
      parse_path_csv(kJoint + "0,0,-1,1,0,0,0\n0.01,0,-1,1.001,0,0,0\n", "p.csv", table, error));
  const InverseKinematics ik(ur5());
  const JointPathResult p = joint_path_from_table(ik, ur5(), table, 0.05, JointVector{});
  EXPECT_EQ(p.status, PathStatus::InvalidSpec);
  EXPECT_NE(p.message.find("p.csv: the path lasts 0.01 s, less than one tick (0.05 s)"),
            std::string::npos)
      << p.message;
  ASSERT_TRUE(
      parse_path_csv(kJoint + "0,0,-1,1,0,0,0\n0.05,0,-1,1.001,0,0,0\n", "p.csv", table, error));
  const JointPathResult one = joint_path_from_table(ik, ur5(), table, 0.05, JointVector{});
  ASSERT_TRUE(one.ok()) << one.message;
  EXPECT_EQ(one.time_s.size(), 2u);
}

// Roll, pitch and yaw are radians: a pose row with an angle beyond +-2 pi (written in degrees) is
// refused with its line and value; 2 pi itself and joint rows beyond it are not refused.
TEST(PathFile, RefusesPoseAnglesBeyondOneTurnAsDegrees) {
  const std::string roll = parse_error(kPose + "0,0.4,0.1,0.3,0,0,0\n1,0.4,0.1,0.3,180,0,0\n");
  EXPECT_NE(roll.find("p.csv:3: roll_rad 180 is beyond one turn"), std::string::npos) << roll;
  EXPECT_NE(roll.find("radians"), std::string::npos) << roll;
  const std::string pitch = parse_error(kPose + "0,0.4,0.1,0.3,0,-90,0\n1,0.4,0.1,0.3,0,0,0\n");
  EXPECT_NE(pitch.find("p.csv:2: pitch_rad -90 is beyond one turn"), std::string::npos) << pitch;
  const std::string yaw = parse_error(kPose + "0,0.4,0.1,0.3,0,0,6.3\n1,0.4,0.1,0.3,0,0,0\n");
  EXPECT_NE(yaw.find("p.csv:2: yaw_rad 6.3 is beyond one turn"), std::string::npos) << yaw;
  PathTable t;
  std::string error;
  EXPECT_TRUE(parse_path_csv(
      kPose + "0,0.4,0.1,0.3,6.283185307179586,-6.2831853,0\n1,0,0,0,0,0,0\n", "p.csv", t, error))
      << error;
  EXPECT_TRUE(parse_path_csv(kJoint + "0,0,0,0,0,0,9\n1,0,0,0,0,0,9\n", "p.csv", t, error))
      << error;
}

TEST(PathFile, CartesianRowsReproduceTheJointRowsTheyCameFrom) {
  // Joint rows on one branch, their poses by forward kinematics as a Cartesian file; inverse
  // kinematics (KDL on this arm) seeded near the first row must give the joint rows back.
  const RobotModel& m = ur5();
  std::string joints = kJoint, poses = kPose;
  for (int k = 0; k <= 50; ++k) {
    const double t = 0.04 * k;
    const JointVector q = {0.1 * std::sin(t), -1.3 + 0.1 * t, 1.6 - 0.05 * t, -0.9, -1.2,
                           0.3 + 0.2 * t};
    const Pose p = fk(m, q);
    const Eigen::Vector3d rpy = p.rotation.eulerAngles(2, 1, 0);  // yaw, pitch, roll
    char row[512];
    std::snprintf(row, sizeof row, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", t, q[0], q[1],
                  q[2], q[3], q[4], q[5]);
    joints += row;
    std::snprintf(row, sizeof row, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", t,
                  p.position_m.x(), p.position_m.y(), p.position_m.z(), rpy[2], rpy[1], rpy[0]);
    poses += row;
  }
  PathTable jt, pt;
  std::string error;
  ASSERT_TRUE(parse_path_csv(joints, "j.csv", jt, error)) << error;
  ASSERT_TRUE(parse_path_csv(poses, "p.csv", pt, error)) << error;
  const InverseKinematics ik(m);
  ASSERT_FALSE(ik.has_analytic());
  const JointVector seed = {0.0, -1.25, 1.55, -0.85, -1.15, 0.25};
  const JointPathResult a = joint_path_from_table(ik, m, jt, 0.01, seed);
  const JointPathResult b = joint_path_from_table(ik, m, pt, 0.01, seed);
  ASSERT_TRUE(a.ok()) << a.message;
  ASSERT_TRUE(b.ok()) << b.message;
  ASSERT_EQ(a.time_s.size(), b.time_s.size());
  double worst = 0.0;
  for (std::size_t k = 0; k < a.time_s.size(); ++k)
    for (std::size_t j = 0; j < kNumJoints; ++j)
      worst = std::fmax(worst, std::fabs(a.position_rad[k][j] - b.position_rad[k][j]));
  EXPECT_LT(worst, 1e-5);
}

TEST(PathFile, EachCartesianRowIsSolvedFromThePreviousRowsJoints) {
  // The tool turns about its axis by 1 rad a second, 5 rad in all: joint 6 must follow it to
  // 5.3 rad (inside its +/-2 pi). Solved from the first row's seed instead, a row more than pi
  // away from it would come back as the same pose with joint 6 a turn lower.
  const RobotModel& m = ur5();
  std::string joints = kJoint, poses = kPose;
  for (int k = 0; k <= 5; ++k) {
    const double t = k;
    const JointVector q = {0.1, -1.3, 1.6, -0.9, -1.2, 0.3 + t};
    const Pose p = fk(m, q);
    const Eigen::Vector3d rpy = p.rotation.eulerAngles(2, 1, 0);  // yaw, pitch, roll
    char row[512];
    std::snprintf(row, sizeof row, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", t, q[0], q[1],
                  q[2], q[3], q[4], q[5]);
    joints += row;
    std::snprintf(row, sizeof row, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", t,
                  p.position_m.x(), p.position_m.y(), p.position_m.z(), rpy[2], rpy[1], rpy[0]);
    poses += row;
  }
  PathTable jt, pt;
  std::string error;
  ASSERT_TRUE(parse_path_csv(joints, "j.csv", jt, error)) << error;
  ASSERT_TRUE(parse_path_csv(poses, "p.csv", pt, error)) << error;
  const InverseKinematics ik(m);
  const JointVector seed = {0.1, -1.3, 1.6, -0.9, -1.2, 0.3};
  const JointPathResult a = joint_path_from_table(ik, m, jt, 0.5, seed);
  const JointPathResult b = joint_path_from_table(ik, m, pt, 0.5, seed);
  ASSERT_TRUE(a.ok()) << a.message;
  ASSERT_TRUE(b.ok()) << b.message;
  ASSERT_EQ(a.time_s.size(), b.time_s.size());
  for (std::size_t k = 0; k < a.time_s.size(); ++k)
    for (std::size_t j = 0; j < kNumJoints; ++j)
      EXPECT_NEAR(b.position_rad[k][j], a.position_rad[k][j], 1e-6) << k << "," << j;
  EXPECT_NEAR(b.position_rad.back()[5], 5.3, 1e-6);
}

TEST(PathFile, AnUnreachablePoseNamesTheRowTheTimeThePoseAndTheSolver) {
  PathTable t;
  std::string error;
  ASSERT_TRUE(parse_path_csv(kPose + "0,0.4,0.1,0.3,3.1,0,0\n0.5,3.0,0.1,0.3,3.1,0,0\n", "far.csv",
                             t, error));
  const InverseKinematics ik(ur5());
  const JointPathResult p = joint_path_from_table(ik, ur5(), t, 0.05, default_ik_seed(ur5()));
  ASSERT_FALSE(p.ok());
  EXPECT_NE(p.message.find("far.csv:3: row at t = 0.5 s: pose (3, 0.1, 0.3) m"), std::string::npos)
      << p.message;
  EXPECT_NE(p.message.find("KDL Newton-Raphson and Levenberg-Marquardt refused it"),
            std::string::npos)
      << p.message;
}

// A seed outside a joint's limits used to fail as the first row's pose "refused" by the solver: the
// seed is named, with the joint and its limits.
TEST(PathFile, AnIkSeedOutsideTheJointLimitsIsBlamedOnTheSeed) {
  PathTable t;
  std::string error;
  ASSERT_TRUE(parse_path_csv(kPose + "0,0.4,0.1,0.3,3.1,0,0\n0.5,0.4,0.1,0.31,3.1,0,0\n", "p.csv",
                             t, error));
  const InverseKinematics ik(ur5());
  JointVector seed = default_ik_seed(ur5());
  ASSERT_TRUE(joint_path_from_table(ik, ur5(), t, 0.05, seed).ok());
  seed[2] = 4.0;  // joint 3 is limited to +-pi
  const JointPathResult p = joint_path_from_table(ik, ur5(), t, 0.05, seed);
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.message.rfind("the IK seed (--ik-seed, ik_seed): joint 3 ('" +
                                ur5().joint_names()[2] + "') at 4 rad is outside its URDF limits [",
                            0),
            0u)
      << p.message;
  EXPECT_EQ(p.message.find("row at"), std::string::npos) << p.message;
}

TEST(PathFile, RefusesJointsOutsideTheirLimitsAndRowsFasterThanTheVelocityLimits) {
  PathTable t;
  std::string error;
  ASSERT_TRUE(parse_path_csv(kJoint + "0,0,0,0,0,0,0\n1,0,0,3.5,0,0,0\n", "lim.csv", t, error));
  const InverseKinematics ik(ur5());
  JointPathResult p = joint_path_from_table(ik, ur5(), t, 0.05, JointVector{});
  ASSERT_FALSE(p.ok());
  EXPECT_NE(p.message.find("lim.csv:3: row at t = 1 s: joint 3 at 3.5 rad is outside its URDF "
                           "limits"),
            std::string::npos)
      << p.message;
  ASSERT_TRUE(parse_path_csv(kJoint + "0,0,0,0,0,0,0\n0.1,0,0,0.5,0,0,0\n", "fast.csv", t, error));
  p = joint_path_from_table(ik, ur5(), t, 0.05, JointVector{});
  ASSERT_FALSE(p.ok());
  EXPECT_NE(p.message.find("joint 3 moves at 5 rad/s from the previous row, above its URDF "
                           "velocity limit 3.15 rad/s"),
            std::string::npos)
      << p.message;
}

TEST(PathFile, AContinuousJointCrossingPiIsUnwrappedNotTurnedBack) {
  LoadResult r = RobotModel::load(std::string(FUZZYPID_ROBOT_TEST_DATA) + "/continuous_wrist.urdf");
  ASSERT_TRUE(r.model) << r.error;
  PathTable t;
  std::string error;
  // Joint 6 goes 3.0 -> 3.1 -> -3.1 (= 3.183) -> -3.0 (= 3.283): forwards through +pi.
  ASSERT_TRUE(parse_path_csv(kJoint + "0,0,-1,1,0,0,3.0\n0.1,0,-1,1,0,0,3.1\n0.2,0,-1,1,0,0,-3.1\n"
                                      "0.3,0,-1,1,0,0,-3.0\n",
                             "wrap.csv", t, error));
  const InverseKinematics ik(*r.model);
  const JointPathResult p = joint_path_from_table(ik, *r.model, t, 0.05, JointVector{});
  ASSERT_TRUE(p.ok()) << p.message;
  EXPECT_NEAR(p.position_rad.back()[5], -3.0 + 2 * kPi, 1e-12);
  for (std::size_t k = 0; k < p.time_s.size(); ++k)
    EXPECT_GT(p.velocity_rad_s[k][5], 0.5);
  // The same rows on a revolute joint limited to +/-2 pi would ask for a turn back at 62 rad/s:
  // refused by the velocity limit.
  const JointPathResult limited =
      joint_path_from_table(InverseKinematics(ur5()), ur5(), t, 0.05, JointVector{});
  EXPECT_FALSE(limited.ok());
}

TEST(PathFile, TheReversedPathRunsBackwardsWithNegatedVelocities) {
  PathTable t;
  std::string error;
  ASSERT_TRUE(parse_path_csv(kJoint + "0,0,-1,1,0,0,0\n1,0.2,-1,1,0,0,0\n2,0.3,-1,1,0,0,0\n",
                             "p.csv", t, error));
  const JointPathResult p =
      joint_path_from_table(InverseKinematics(ur5()), ur5(), t, 0.1, JointVector{});
  ASSERT_TRUE(p.ok());
  const JointPathResult b = reversed(p);
  const std::size_t n = p.time_s.size();
  for (std::size_t k = 0; k < n; ++k) {
    EXPECT_NEAR(b.time_s[k], 0.1 * static_cast<double>(k), 1e-12);
    EXPECT_EQ(b.position_rad[k][0], p.position_rad[n - 1 - k][0]);
    EXPECT_EQ(b.velocity_rad_s[k][0], -p.velocity_rad_s[n - 1 - k][0]);
  }
}

}  // namespace
}  // namespace fuzzypid::robot
