// The closed-form (Pieper) inverse kinematics of the ER50-C20.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include <gtest/gtest.h>

#include "fuzzypid/robot/analytic_ik.hpp"
#include "fuzzypid/robot/ik.hpp"
#include "test_support.hpp"

namespace fuzzypid::robot {
namespace {

using test::bundled_model;
using test::fk;
using test::position_error;
using test::rotation_error;

const AnalyticIk& solver() {
  static const AnalyticIk ik = [] {
    std::string error;
    auto s = AnalyticIk::from_model(bundled_model(), er50_c20_dh(), &error);
    if (!s) {
      std::fprintf(stderr, "%s\n", error.c_str());
      std::abort();
    }
    return *s;
  }();
  return ik;
}

TEST(AnalyticIk, RoundTripsTenThousandRandomConfigurations) {
  const RobotModel& m = bundled_model();
  auto rng = test::seeded_rng(0x5eed1234, "AnalyticIk.RoundTrips");
  constexpr int kSamples = 10000;
  int solved = 0;
  int recovered_own_seed = 0;
  double worst_position = 0.0;
  double worst_rotation = 0.0;
  for (int n = 0; n < kSamples; ++n) {
    const JointVector q = test::random_within(m, rng);
    const JointVector seed = test::random_within(m, rng);  // an unrelated seed: any branch will do
    const Pose target = fk(m, q);
    JointVector out{};
    const IkStatus s = solver().solve(target, seed, out);
    if (s != IkStatus::Ok) continue;
    ++solved;
    ASSERT_TRUE(m.within_limits(out)) << "n=" << n;
    const Pose reached = fk(m, out);
    worst_position = std::fmax(worst_position, position_error(reached, target));
    worst_rotation = std::fmax(worst_rotation, rotation_error(reached, target));
    ASSERT_LT(position_error(reached, target), 1e-9) << "n=" << n;
    ASSERT_LT(rotation_error(reached, target), 1e-9) << "n=" << n;

    // Seeded with the configuration itself, the nearest solution is that configuration.
    JointVector back{};
    if (solver().solve(target, q, back) == IkStatus::Ok) {
      double d = 0.0;
      for (std::size_t j = 0; j < kNumJoints; ++j)
        d = std::fmax(d, std::fabs(back[j] - q[j]));
      if (d < 1e-9) ++recovered_own_seed;
    }
  }
  const double rate = static_cast<double>(solved) / kSamples;
  std::printf(
      "[ measured ] closed form: %d/%d solved (%.2f %%), own seed recovered %d, worst "
      "error %.3g m %.3g rad\n",
      solved, kSamples, 100.0 * rate, recovered_own_seed, worst_position, worst_rotation);
  EXPECT_GE(rate, 0.999);
  EXPECT_GE(recovered_own_seed, static_cast<int>(0.999 * kSamples));
}

TEST(AnalyticIk, EveryBranchReachesTheTarget) {
  const RobotModel& m = bundled_model();
  auto rng = test::seeded_rng(99, "AnalyticIk.EveryBranchReachesTheTarget");
  for (int n = 0; n < 1000; ++n) {
    const Pose target = fk(m, test::random_within(m, rng));
    const IkBranches b = solver().solve_all(target);
    ASSERT_EQ(b.status, IkStatus::Ok);
    ASSERT_GE(b.count, 2u);
    ASSERT_LE(b.count, 8u);
    bool any_within = false;
    for (std::size_t k = 0; k < b.count; ++k) {
      const Pose reached = fk(m, b.solutions[k]);
      EXPECT_LT(position_error(reached, target), 1e-9);
      EXPECT_LT(rotation_error(reached, target), 1e-9);
      any_within = any_within || b.within_limits[k];
    }
    EXPECT_TRUE(any_within);
  }
}

TEST(AnalyticIk, PointOutOfReachIsUnreachable) {
  Pose target;
  target.position_m = {2.5, 0.0, 0.563};  // beyond a1 + a2 + sqrt(a3² + d4²) = 2.147 m
  JointVector out{};
  EXPECT_EQ(solver().solve(target, JointVector{}, out), IkStatus::Unreachable);
  // No inner void: a point near one shoulder position is reached by the other J1 branch, so only
  // points far away are unreachable.
  target.position_m = {0.0, 0.3, -2.0};
  EXPECT_EQ(solver().solve(target, JointVector{}, out), IkStatus::Unreachable);
}

TEST(AnalyticIk, PoseNeedingJ5BeyondItsRangeIsJointLimits) {
  // q5 = 2.5 rad > 120°: every one of the 8 branches of this pose breaks some limit.
  const JointVector q = {0.0, -0.3, 0.3, 0.0, 2.5, 0.0};
  const Pose target = fk(bundled_model(), q);
  const IkBranches b = solver().solve_all(target);
  ASSERT_EQ(b.count, 8u);
  for (std::size_t k = 0; k < b.count; ++k)
    EXPECT_FALSE(b.within_limits[k]);
  JointVector out = {1, 2, 3, 4, 5, 6};
  EXPECT_EQ(solver().solve(target, JointVector{}, out), IkStatus::JointLimits);
  EXPECT_EQ(out, (JointVector{1, 2, 3, 4, 5, 6}));  // untouched on failure
}

TEST(AnalyticIk, WristSingularityKeepsTheSeedsJ4) {
  const JointVector q = {0.2, -0.5, 0.4, 0.0, 0.0, 0.3};  // q5 = 0: only q4 + q6 is determined
  const Pose target = fk(bundled_model(), q);
  const JointVector seed = {0.2, -0.5, 0.4, 0.7, 0.1, -0.2};
  JointVector out{};
  ASSERT_EQ(solver().solve(target, seed, out), IkStatus::Singular);
  EXPECT_NEAR(out[3], 0.7, 1e-12);
  EXPECT_NEAR(out[3] + out[5], 0.3, 1e-12);
  const Pose reached = fk(bundled_model(), out);
  EXPECT_LT(position_error(reached, target), 1e-12);
  EXPECT_LT(rotation_error(reached, target), 1e-9);
}

TEST(AnalyticIk, WristCenterOnTheFirstAxisKeepsTheSeedsJ1) {
  Pose target;
  target.position_m = {0.0, 0.0, 1.5};
  JointVector out{};
  const JointVector seed = {0.4, -1.0, 0.0, 0.0, 0.5, 0.0};
  ASSERT_EQ(solver().solve(target, seed, out), IkStatus::Singular);
  EXPECT_NEAR(out[0], 0.4, 1e-12);
  const Pose reached = fk(bundled_model(), out);
  EXPECT_LT(position_error(reached, target), 1e-12);
  EXPECT_LT(rotation_error(reached, target), 1e-9);
}

TEST(AnalyticIk, RejectsNonFiniteAndImproperInput) {
  const Pose good = fk(bundled_model(), {0.1, -0.2, 0.3, 0.4, 0.5, 0.6});
  JointVector out{};
  Pose bad = good;
  bad.position_m.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(solver().solve(bad, JointVector{}, out), IkStatus::InvalidInput);
  bad = good;
  bad.rotation *= 2.0;  // not orthonormal
  EXPECT_EQ(solver().solve(bad, JointVector{}, out), IkStatus::InvalidInput);
  bad = good;
  bad.rotation.col(2) *= -1.0;  // a reflection
  EXPECT_EQ(solver().solve(bad, JointVector{}, out), IkStatus::InvalidInput);
  JointVector seed{};
  seed[2] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(solver().solve(good, seed, out), IkStatus::InvalidInput);
}

TEST(AnalyticIk, IsRefusedForAModelWithDifferentGeometry) {
  DhParameters other = er50_c20_dh();
  other.a2_m = 1.0;
  std::string error;
  EXPECT_FALSE(AnalyticIk::from_model(bundled_model(), other, &error).has_value());
  EXPECT_NE(error.find("Table 1"), std::string::npos);
}

TEST(AnalyticIk, SolveTakesMicroseconds) {
  const RobotModel& m = bundled_model();
  auto rng = test::seeded_rng(3, "AnalyticIk.SolveTakesMicroseconds");
  std::vector<Pose> targets;
  targets.reserve(2000);
  for (int n = 0; n < 2000; ++n)
    targets.push_back(fk(m, test::random_within(m, rng)));
  JointVector out{};
  int ok = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (const Pose& t : targets)
    ok += solver().solve(t, JointVector{}, out) == IkStatus::Ok;
  const double us =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() /
      static_cast<double>(targets.size());
  std::printf("[ measured ] closed form: %.2f us per solve (%d ok)\n", us, ok);
  EXPECT_LT(us, 200.0);  // generous: sanitizer and debug builds
}

}  // namespace
}  // namespace fuzzypid::robot
