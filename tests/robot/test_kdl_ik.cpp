// KDL's numerical IK (NR_JL and LMA) against the closed form.
#include <chrono>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "fuzzypid/robot/ik.hpp"
#include "fuzzypid_support/uniform_real.hpp"
#include "test_support.hpp"

namespace fuzzypid::robot {
namespace {

using test::bundled_model;
using test::fk;
using test::position_error;
using test::rotation_error;

struct Rates {
  int ok = 0;
  int agree = 0;
  int both = 0;
  double seconds = 0.0;
};

// Targets FK(q) for random q within limits; seeds q + U(-spread, spread) clamped into the limits
// (spread = 0 means the fixed home seed q = 0).
Rates measure(const InverseKinematics& ik, IkSolver solver, double spread, int samples,
              std::uint64_t seed) {
  const RobotModel& m = bundled_model();
  auto rng = test::seeded_rng(seed, to_string(solver));
  fuzzypid::support::UniformReal<double> noise(-spread, spread);
  Rates r;
  for (int n = 0; n < samples; ++n) {
    const JointVector q = test::random_within(m, rng);
    JointVector init{};
    if (spread > 0.0) {
      for (std::size_t j = 0; j < kNumJoints; ++j) {
        init[j] = std::fmin(std::fmax(q[j] + noise(rng), m.lower_limits_rad()[j]),
                            m.upper_limits_rad()[j]);
      }
    }
    const Pose target = fk(m, q);
    JointVector out{};
    const auto t0 = std::chrono::steady_clock::now();
    const IkStatus s = ik.solve(solver, target, init, out);
    r.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (s != IkStatus::Ok) continue;
    ++r.ok;
    EXPECT_TRUE(m.within_limits(out));
    const Pose reached = fk(m, out);
    EXPECT_LT(position_error(reached, target), 1e-6);
    EXPECT_LT(rotation_error(reached, target), 1e-6);
    JointVector closed{};
    if (ik.solve(IkSolver::Analytic, target, init, closed) == IkStatus::Ok) {
      ++r.both;
      const Pose c = fk(m, closed);
      // Agreement is FK-wise: both reach the same pose (possibly on different branches).
      if (position_error(c, reached) < 1e-6 && rotation_error(c, reached) < 1e-6) ++r.agree;
    }
  }
  std::printf(
      "[ measured ] %s, seed %s: %d/%d ok (%.1f %%), agree with closed form %d/%d, "
      "%.1f us mean\n",
      to_string(solver), spread > 0.0 ? "q +- spread" : "home (q = 0)", r.ok, samples,
      100.0 * r.ok / samples, r.agree, r.both, 1e6 * r.seconds / samples);
  return r;
}

const InverseKinematics& ik() {
  static const InverseKinematics s(bundled_model());
  return s;
}

TEST(KdlIk, ClosedFormIsAvailableForTheBundledModel) {
  EXPECT_TRUE(ik().has_analytic());
}

TEST(KdlIk, NewtonRaphsonWithLimitsAgreesWithTheClosedFormNearTheSeed) {
  constexpr int kSamples = 2000;
  const Rates r = measure(ik(), IkSolver::KdlNr, 0.3, kSamples, 11);  // measured 96.8 % ok
  EXPECT_EQ(r.agree, r.both);
  EXPECT_GE(r.ok, static_cast<int>(0.93 * kSamples));
}

TEST(KdlIk, LevenbergMarquardtAgreesWithTheClosedFormNearTheSeed) {
  constexpr int kSamples = 2000;
  const Rates r = measure(ik(), IkSolver::KdlLma, 0.3, kSamples, 12);  // measured 99.8 % ok
  EXPECT_EQ(r.agree, r.both);
  EXPECT_GE(r.ok, static_cast<int>(0.98 * kSamples));
}

TEST(KdlIk, FromTheHomeSeedBothSolversOftenFailAndSaySo) {
  constexpr int kSamples = 500;
  const Rates nr = measure(ik(), IkSolver::KdlNr, 0.0, kSamples, 13);
  const Rates lma = measure(ik(), IkSolver::KdlLma, 0.0, kSamples, 14);
  EXPECT_EQ(nr.agree, nr.both);
  EXPECT_EQ(lma.agree, lma.both);
  // Measured 35 % (NR) and 74 % (LMA) with the seeds below; the bounds leave room for noise.
  EXPECT_GE(nr.ok, static_cast<int>(0.25 * kSamples));
  EXPECT_GE(lma.ok, static_cast<int>(0.60 * kSamples));
}

TEST(KdlIk, UnreachableTargetIsNoConvergence) {
  Pose target;
  target.position_m = {3.0, 0.0, 0.5};
  JointVector out{};
  EXPECT_EQ(ik().solve(IkSolver::KdlNr, target, JointVector{}, out), IkStatus::NoConvergence);
  EXPECT_EQ(ik().solve(IkSolver::KdlLma, target, JointVector{}, out), IkStatus::NoConvergence);
}

TEST(KdlIk, SolutionOutsideTheLimitsIsJointLimits) {
  // q5 = 2.5 rad (> 120°) seeded exactly: both solvers stop at once on the out-of-range solution
  // (NR_JL clamps only the iterates it computes), and the limit check catches it.
  const JointVector q = {0.0, -0.3, 0.3, 0.0, 2.5, 0.0};
  const Pose target = fk(bundled_model(), q);
  JointVector out{};
  EXPECT_EQ(ik().solve(IkSolver::KdlLma, target, q, out), IkStatus::JointLimits);
  EXPECT_EQ(ik().solve(IkSolver::KdlNr, target, q, out), IkStatus::JointLimits);
}

TEST(KdlIk, SolverNamesRoundTrip) {
  for (IkSolver s : {IkSolver::Analytic, IkSolver::KdlNr, IkSolver::KdlLma}) {
    EXPECT_EQ(ik_solver_from_string(to_string(s)), s);
  }
  EXPECT_FALSE(ik_solver_from_string("kdl").has_value());
}

}  // namespace
}  // namespace fuzzypid::robot
