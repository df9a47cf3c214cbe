// The section 6 Cartesian path and its joint-space reference.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "fuzzypid/robot/path.hpp"
#include "test_support.hpp"

namespace fuzzypid::robot {
namespace {

using test::bundled_model;
using test::fk;

// Distance from p to the segment a-b.
double distance_to_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                           const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double s = std::fmin(1.0, std::fmax(0.0, (p - a).dot(ab) / ab.squaredNorm()));
  return (a + s * ab - p).norm();
}

TEST(Path, PaperJointVectorsDoNotReachAAndBUnderTable1) {
  // Documented discrepancy (docs/robot.md): FK of the section 6 joint vectors misses A and B.
  const CartesianPathSpec spec = paper_path_spec();
  const Pose start = fk(bundled_model(), kPaperStartJoints);
  const Pose end = fk(bundled_model(), kPaperEndJoints);
  const double to_a = (start.position_m - spec.start_m).norm();
  const double to_b = (end.position_m - spec.end_m).norm();
  std::printf(
      "[ measured ] FK(theta) = (%.4f, %.4f, %.4f) m, %.4f m from A; FK(theta') = "
      "(%.4f, %.4f, %.4f) m, %.4f m from B\n",
      start.position_m.x(), start.position_m.y(), start.position_m.z(), to_a, end.position_m.x(),
      end.position_m.y(), end.position_m.z(), to_b);
  EXPECT_NEAR(to_a, 0.9085, 1e-3);
  EXPECT_NEAR(to_b, 0.8321, 1e-3);
}

TEST(Path, PaperSpecIsSection6InMetres) {
  const CartesianPathSpec spec = paper_path_spec();
  EXPECT_EQ(spec.start_m, Eigen::Vector3d(1.350, 0.530, 1.250));
  EXPECT_EQ(spec.end_m, Eigen::Vector3d(1.615, 0.240, 0.490));
  EXPECT_EQ(spec.samples, 101u);
  EXPECT_EQ(spec.duration_s, 5.0);
  EXPECT_EQ(spec.orientation, OrientationMode::Fixed);
  // The orientation is that of FK(theta), the paper's start joint vector.
  const Pose start = fk(bundled_model(), kPaperStartJoints);
  EXPECT_LT((spec.start_rotation - start.rotation).cwiseAbs().maxCoeff(), 1e-12);
}

void expect_on_line(const JointPathResult& r, const CartesianPathSpec& spec, double tolerance) {
  const RobotModel& m = bundled_model();
  ASSERT_EQ(r.position_rad.size(), spec.samples);
  ASSERT_EQ(r.velocity_rad_s.size(), spec.samples);
  ASSERT_EQ(r.time_s.size(), spec.samples);
  for (std::size_t k = 0; k < spec.samples; ++k) {
    const Pose reached = fk(m, r.position_rad[k]);
    const double s = static_cast<double>(k) / static_cast<double>(spec.samples - 1);
    const Eigen::Vector3d expected = (1.0 - s) * spec.start_m + s * spec.end_m;
    EXPECT_LT((reached.position_m - expected).norm(), tolerance) << "sample " << k;
    EXPECT_LT(distance_to_segment(reached.position_m, spec.start_m, spec.end_m), tolerance);
    EXPECT_LT(test::rotation_error(reached, r.poses[k]), tolerance) << "sample " << k;
    EXPECT_TRUE(m.within_limits(r.position_rad[k]));
    EXPECT_NEAR(r.time_s[k], spec.duration_s * s, 1e-12);
  }
}

TEST(Path, PaperPathIsSolvedOnTheLineWithoutBranchJumps) {
  const CartesianPathSpec spec = paper_path_spec();
  const JointPathResult r =
      plan_joint_path(bundled_model(), spec, IkSolver::Analytic, kPaperStartJoints);
  ASSERT_TRUE(r.ok()) << r.message;
  expect_on_line(r, spec, 1e-9);
  for (std::size_t k = 1; k < r.position_rad.size(); ++k) {
    for (std::size_t j = 0; j < kNumJoints; ++j) {
      EXPECT_LT(std::fabs(r.position_rad[k][j] - r.position_rad[k - 1][j]), 0.05)
          << "sample " << k << " joint " << j + 1;
    }
  }
  EXPECT_TRUE(r.within_velocity_limits);
  const JointVector& q0 = r.position_rad.front();
  std::printf("[ measured ] path start q = %.4f %.4f %.4f %.4f %.4f %.4f rad\n", q0[0], q0[1],
              q0[2], q0[3], q0[4], q0[5]);
  const JointVector& vmax = r.max_speed_rad_s;
  std::printf("[ measured ] path max |qd| = %.4f %.4f %.4f %.4f %.4f %.4f rad/s\n", vmax[0],
              vmax[1], vmax[2], vmax[3], vmax[4], vmax[5]);
}

TEST(Path, VelocitiesAreCentralDifferencesAndOneSidedAtTheEnds) {
  const CartesianPathSpec spec = paper_path_spec();
  const JointPathResult r =
      plan_joint_path(bundled_model(), spec, IkSolver::Analytic, kPaperStartJoints);
  ASSERT_TRUE(r.ok()) << r.message;
  const double h = 0.05;
  const auto& q = r.position_rad;
  const auto& v = r.velocity_rad_s;
  for (std::size_t j = 0; j < kNumJoints; ++j) {
    EXPECT_DOUBLE_EQ(v[0][j], (q[1][j] - q[0][j]) / h);
    EXPECT_DOUBLE_EQ(v[50][j], (q[51][j] - q[49][j]) / (2 * h));
    EXPECT_DOUBLE_EQ(v[100][j], (q[100][j] - q[99][j]) / h);
  }
}

TEST(Path, KdlSolversFollowTheSameLine) {
  const CartesianPathSpec spec = paper_path_spec();
  for (IkSolver s : {IkSolver::KdlNr, IkSolver::KdlLma}) {
    // Start KDL from the closed-form solution of A so that it stays on the same branch.
    const JointPathResult exact =
        plan_joint_path(bundled_model(), spec, IkSolver::Analytic, kPaperStartJoints);
    ASSERT_TRUE(exact.ok());
    const JointPathResult r = plan_joint_path(bundled_model(), spec, s, exact.position_rad[0]);
    ASSERT_TRUE(r.ok()) << to_string(s) << ": " << r.message;
    expect_on_line(r, spec, 1e-6);
  }
}

TEST(Path, SlerpEndsAtTheEndOrientation) {
  CartesianPathSpec spec = paper_path_spec();
  spec.orientation = OrientationMode::Slerp;
  spec.end_rotation = fk(bundled_model(), kPaperEndJoints).rotation;
  const JointPathResult r =
      plan_joint_path(bundled_model(), spec, IkSolver::Analytic, kPaperStartJoints);
  ASSERT_TRUE(r.ok()) << r.message;
  const Pose last = fk(bundled_model(), r.position_rad.back());
  EXPECT_LT((last.rotation - spec.end_rotation).cwiseAbs().maxCoeff(), 1e-9);
  expect_on_line(r, spec, 1e-9);
}

TEST(Path, UnreachableSampleIsReportedWithItsIndex) {
  CartesianPathSpec spec = paper_path_spec();
  spec.end_m = {3.5, 0.0, 0.5};   // leaves the workspace part-way
  spec.max_joint_step_rad = 4.0;  // the elbow straightens fast near the boundary
  const JointPathResult r =
      plan_joint_path(bundled_model(), spec, IkSolver::Analytic, kPaperStartJoints);
  EXPECT_EQ(r.status, PathStatus::IkFailed);
  EXPECT_EQ(r.ik_status, IkStatus::Unreachable);
  EXPECT_GT(r.first_failure, 0u);
  EXPECT_LT(r.first_failure, spec.samples);
  EXPECT_EQ(r.position_rad.size(), r.first_failure);
  EXPECT_NE(r.message.find("unreachable"), std::string::npos);
}

TEST(Path, BranchJumpIsDetected) {
  // A threshold below the per-sample motion stands in for a branch flip.
  CartesianPathSpec spec = paper_path_spec();
  spec.max_joint_step_rad = 1e-4;
  const JointPathResult r =
      plan_joint_path(bundled_model(), spec, IkSolver::Analytic, kPaperStartJoints);
  EXPECT_EQ(r.status, PathStatus::JointJump);
  EXPECT_EQ(r.first_failure, 1u);
}

TEST(Path, InvalidSpecIsRejected) {
  CartesianPathSpec spec = paper_path_spec();
  spec.samples = 1;
  EXPECT_EQ(plan_joint_path(bundled_model(), spec, IkSolver::Analytic, {}).status,
            PathStatus::InvalidSpec);
  spec = paper_path_spec();
  spec.duration_s = 0.0;
  EXPECT_EQ(plan_joint_path(bundled_model(), spec, IkSolver::Analytic, {}).status,
            PathStatus::InvalidSpec);
  spec = paper_path_spec();
  spec.start_rotation *= 3.0;
  EXPECT_EQ(plan_joint_path(bundled_model(), spec, IkSolver::Analytic, {}).status,
            PathStatus::InvalidSpec);
}

}  // namespace
}  // namespace fuzzypid::robot
