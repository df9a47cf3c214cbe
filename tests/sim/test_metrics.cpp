// The tracking metrics of sim_ab (fuzzypid/sim/metrics.hpp) on hand-computable signals.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "fuzzypid/sim/condition.hpp"
#include "fuzzypid/sim/metrics.hpp"

namespace {

using fuzzypid::sim::joint_metrics;

TEST(JointMetrics, ErrorThatDecaysIntoTheBandSettlesAtTheFirstSampleInside) {
  // Reference constant at 1, joint starts at 0 (travel 1, band 0.02); e = 0.5^k.
  std::vector<double> t, ref, theta, e;
  for (int k = 0; k < 20; ++k) {
    t.push_back(0.05 * k);
    ref.push_back(1.0);
    e.push_back(std::pow(0.5, k));
    theta.push_back(1.0 - e.back());
  }
  const auto m = joint_metrics(t, ref, theta, e, 0.05);
  // 0.5^5 = 0.03125 > 0.02 is the last sample outside; 0.5^6 is inside.
  EXPECT_DOUBLE_EQ(m.settling_time_s, t[6]);
  EXPECT_DOUBLE_EQ(m.overshoot_pct, 0.0);
  EXPECT_DOUBLE_EQ(m.max_abs_error_rad, 1.0);
  double iae = 0, itae = 0, sq = 0;
  for (int k = 0; k < 20; ++k) {
    iae += e[k] * 0.05;
    itae += t[k] * e[k] * 0.05;
    sq += e[k] * e[k];
  }
  EXPECT_NEAR(m.iae, iae, 1e-15);
  EXPECT_NEAR(m.itae, itae, 1e-15);
  EXPECT_NEAR(m.rms_error_rad, std::sqrt(sq / 20), 1e-15);
}

TEST(JointMetrics, OvershootIsTheExcursionPastTheReferenceRelativeToTravel) {
  // Starts 1 behind (e > 0), then runs 0.1 past the reference (e = -0.1), then settles.
  const std::vector<double> t{0, 0.05, 0.1, 0.15};
  const std::vector<double> ref{1, 1, 1, 1};
  const std::vector<double> e{1.0, -0.1, 0.0, 0.0};
  std::vector<double> theta;
  for (std::size_t k = 0; k < e.size(); ++k)
    theta.push_back(ref[k] - e[k]);
  const auto m = joint_metrics(t, ref, theta, e, 0.05);
  EXPECT_NEAR(m.overshoot_pct, 10.0, 1e-12);
  EXPECT_DOUBLE_EQ(m.settling_time_s, 0.1);
}

TEST(JointMetrics, NotSettledWhenTheLastSampleIsOutsideTheBand) {
  const std::vector<double> t{0, 0.05}, ref{1, 1}, theta{0, 0.5}, e{1, 0.5};
  EXPECT_EQ(joint_metrics(t, ref, theta, e, 0.05).settling_time_s,
            std::numeric_limits<double>::infinity());
}

TEST(PulseTrain, AlternatesSignAndIsZeroOutsideItsWindow) {
  const fuzzypid::sim::PulseTrain p{1.0, 4.0, 0.5, 0.1, 0.5};
  EXPECT_EQ(p.at(0.9), 0.0);
  EXPECT_EQ(p.at(1.05), 0.5);
  EXPECT_EQ(p.at(1.2), 0.0);
  EXPECT_EQ(p.at(1.55), -0.5);
  EXPECT_EQ(p.at(4.0), 0.0);
}

TEST(Scenarios, PaperComesFirstAndNamesAreUnique) {
  const auto& all = fuzzypid::sim::scenarios();
  ASSERT_FALSE(all.empty());
  EXPECT_EQ(all.front().name, "paper");
  for (std::size_t i = 0; i < all.size(); ++i)
    for (std::size_t j = i + 1; j < all.size(); ++j)
      EXPECT_NE(all[i].name, all[j].name);
  EXPECT_EQ(fuzzypid::sim::find_scenario("nope"), nullptr);
}

}  // namespace
