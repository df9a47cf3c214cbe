// The tracking and drive metrics of sim_ab (fuzzypid/sim/metrics.hpp) and the fault monitor
// (fuzzypid/sim/faults.hpp) on hand-computable signals.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "fuzzypid/sim/condition.hpp"
#include "fuzzypid/sim/faults.hpp"
#include "fuzzypid/sim/metrics.hpp"

namespace {

using fuzzypid::sim::joint_metrics;
namespace sim = fuzzypid::sim;
constexpr double kPi = 3.14159265358979323846;

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

TEST(JointMetrics, OvershootOnAClosedContourIsRelativeToTheExcursionOfTheReference) {
  // The reference goes 0 -> 1 -> 0 (closed: it ends where it starts); the joint starts 0.05
  // behind (e_0 = 0.05) and at one sample runs 0.1 past it (e = -0.1). Travel is only the start
  // error, 0.05: relative to it the overshoot would read 200 %; relative to the excursion 1 it
  // is 10 %.
  std::vector<double> t, ref, theta, e;
  const int n = 41;
  for (int k = 0; k < n; ++k) {
    t.push_back(0.05 * k);
    ref.push_back(std::sin(kPi * k / (n - 1)));
    e.push_back(k == 0 ? 0.05 : (k == 20 ? -0.1 : 0.0));
    theta.push_back(ref.back() - e.back());
  }
  ref.back() = 0.0;  // exactly closed
  theta.back() = 0.0;
  EXPECT_NEAR(joint_metrics(t, ref, theta, e, 0.05).overshoot_pct, 10.0, 1e-9);
  // Open (the reference ends at 0.5, half its excursion away from its start): relative to the
  // travel 0.5 + 0.05 as before.
  for (int k = 20; k < n; ++k)
    ref[static_cast<std::size_t>(k)] = std::max(ref[static_cast<std::size_t>(k)], 0.5);
  for (int k = 0; k < n; ++k)
    theta[static_cast<std::size_t>(k)] =
        ref[static_cast<std::size_t>(k)] - e[static_cast<std::size_t>(k)];
  EXPECT_NEAR(joint_metrics(t, ref, theta, e, 0.05).overshoot_pct, 100.0 * 0.1 / 0.55, 1e-9);
}

TEST(DriveMetrics, ACommandAlternatingEveryTickReversesAndChangesSignOnEveryTick) {
  std::vector<double> u(50);
  for (std::size_t k = 0; k < u.size(); ++k)
    u[k] = k % 2 == 0 ? 3.0 : -3.0;
  EXPECT_DOUBLE_EQ(sim::reversals_pct(u), 100.0);
  EXPECT_DOUBLE_EQ(sim::sign_changes_pct(u), 100.0);
}

TEST(DriveMetrics, ASineReversesOnlyAtItsExtrema) {
  // Two periods, 50 samples each, offset by a quarter step so that no sample is an extremum or
  // a zero: four extrema (pi/2, 3pi/2, 5pi/2, 7pi/2) over the K - 2 ticks on which a reversal
  // can fall, four zero crossings (pi, 2pi, 3pi, 4pi) over the K - 1 ticks.
  const int n = 101;
  std::vector<double> u(n);
  for (int k = 0; k < n; ++k)
    u[static_cast<std::size_t>(k)] = 2.0 * std::sin(2.0 * kPi * (k + 0.25) / 50.0);
  EXPECT_NEAR(sim::reversals_pct(u), 100.0 * 4 / (n - 2), 1e-12);
  EXPECT_NEAR(sim::sign_changes_pct(u), 100.0 * 4 / (n - 1), 1e-12);
}

TEST(DriveMetrics, ReversalsOfRingingIgnoreAConstantOffsetAndChangesBelowOnePercentOfTheRange) {
  // u_k = 0.9^k (-1)^k: range 1 - (-0.9) = 1.9, threshold h = 0.019; |u_k - u_{k-1}| =
  // 1.9 * 0.9^(k-1) > h while 0.9^(k-1) > 0.01, i.e. for k <= 44: reversals on ticks 2..44,
  // 43 of the K - 2 = 58.
  std::vector<double> ring, offset;
  for (int k = 0; k < 60; ++k) {
    ring.push_back(std::pow(0.9, k) * (k % 2 == 0 ? 1.0 : -1.0));
    offset.push_back(ring.back() + 50.0);  // gravity's share of the command
  }
  EXPECT_NEAR(sim::reversals_pct(ring), 100.0 * 43 / 58, 1e-12);
  EXPECT_DOUBLE_EQ(sim::reversals_pct(offset), sim::reversals_pct(ring));
  // The offset command never changes sign; the ringing one on every tick.
  EXPECT_DOUBLE_EQ(sim::sign_changes_pct(offset), 0.0);
  EXPECT_DOUBLE_EQ(sim::sign_changes_pct(ring), 100.0);
}

TEST(DriveMetrics, AZeroCommandIsNoSign) {
  // 1, 0, -1, -2, 0, 3: changes on the third sample (-1 after 1) and the last (3 after -2).
  EXPECT_NEAR(sim::sign_changes_pct({1, 0, -1, -2, 0, 3}), 100.0 * 2 / 5, 1e-12);
  EXPECT_DOUBLE_EQ(sim::sign_changes_pct({0, 0, 0}), 0.0);
  EXPECT_DOUBLE_EQ(sim::reversals_pct({5, 5, 5, 5}), 0.0);
  EXPECT_DOUBLE_EQ(sim::reversals_pct({1, -1}), 0.0);  // K < 3
}

TEST(DriveMetrics, TorqueOfARampHasItsSlopeAsVariationPerSecond) {
  // tau_k = 2 k N·m at t_k = 0.1 k s, k = 0..10: total variation 20 N·m over 1 s; RMS
  // 2 sqrt(sum k^2 / 11) = 2 sqrt(35); three of the eleven ticks at a limit.
  std::vector<double> t, u, tau;
  std::vector<char> sat;
  for (int k = 0; k <= 10; ++k) {
    t.push_back(0.1 * k);
    u.push_back(1.0);
    tau.push_back(2.0 * k);
    sat.push_back(k >= 8 ? 1 : 0);
  }
  const sim::DriveMetrics m = sim::drive_metrics(t, u, tau, sat);
  EXPECT_NEAR(m.torque_variation_nm_per_s, 20.0, 1e-12);
  EXPECT_NEAR(m.tau_rms_nm, 2.0 * std::sqrt(35.0), 1e-12);
  EXPECT_NEAR(m.saturated_pct, 100.0 * 3 / 11, 1e-12);
  EXPECT_DOUBLE_EQ(m.reversals_pct, 0.0);
  EXPECT_DOUBLE_EQ(m.sign_changes_pct, 0.0);
  // A torque going up and back down: the variation counts both ways.
  const std::vector<double> up_down{0, 3, 6, 3, 0};
  EXPECT_NEAR(sim::drive_metrics({0, 1, 2, 3, 4}, up_down, up_down, {0, 0, 0, 0, 0})
                  .torque_variation_nm_per_s,
              12.0 / 4.0, 1e-12);
}

// A limit cycle is kLimitCycleTicks consecutive ticks of saturated torque with alternating sign:
// one tick fewer, a repeated sign, a tick off the limit or a zero torque restart the count.
TEST(FaultMonitor, ALimitCycleIsTenConsecutiveSaturatedTicksOfAlternatingSign) {
  const fuzzypid::robot::JointVector zero{};
  sim::FaultMonitor m;
  std::array<bool, 6> sat{};
  sat[3] = true;  // joint 4 at its limit
  double t = 0.0;
  const auto tick = [&](double tau4, bool at_limit) {
    sat[3] = at_limit;
    t += 0.05;
    return m.observe(t, zero, zero, {0, 0, 0, tau4, 0, 0}, sat);
  };
  // Nine alternating saturated ticks: no fault.
  for (std::size_t k = 0; k + 1 < sim::kLimitCycleTicks; ++k)
    EXPECT_FALSE(tick(k % 2 == 0 ? 300.0 : -300.0, true)) << k;
  // The same sign again (the ninth was +300) restarts the run at 1: eight more alternating
  // ticks make nine.
  EXPECT_FALSE(tick(300.0, true));
  for (std::size_t k = 0; k + 2 < sim::kLimitCycleTicks; ++k)
    EXPECT_FALSE(tick(k % 2 == 0 ? -300.0 : 300.0, true)) << k;
  // A tick off the limit breaks it too.
  EXPECT_FALSE(tick(100.0, false));
  EXPECT_EQ(m.faults().ticks, 0u);
  // Ten in a row: the tenth faults, and every further one.
  for (std::size_t k = 0; k < sim::kLimitCycleTicks + 2; ++k)
    EXPECT_EQ(tick(k % 2 == 0 ? 300.0 : -300.0, true), k + 1 >= sim::kLimitCycleTicks) << k;
  const sim::TrackingFaults& f = m.faults();
  EXPECT_EQ(f.limit_cycle[3].ticks, 3u);
  EXPECT_EQ(f.ticks, 3u);
  EXPECT_DOUBLE_EQ(f.limit_cycle[3].first_value_rad, -300.0);  // the tenth tick's torque
  EXPECT_EQ(f.divergence[3].ticks, 0u);
  const auto lines = sim::describe(f, 1.0, zero, zero);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NE(lines[0].find("joint 4: limit cycle: torque on its limits with alternating sign"),
            std::string::npos)
      << lines[0];
  // Saturated on one side for long (a large step): never a cycle.
  sim::FaultMonitor push;
  for (int k = 0; k < 50; ++k)
    EXPECT_FALSE(push.observe(0.05 * k, zero, zero, {0, 0, 0, 300.0, 0, 0}, sat));
}

TEST(FaultMonitor, NamesTheFirstTickOfEachJointsDivergenceAndLimitViolation) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // Joint 6 continuous (no limits), joint 2 limited to [-1, 1].
  const fuzzypid::robot::JointVector lower{-3, -1, -3, -3, -3, -kInf};
  const fuzzypid::robot::JointVector upper{3, 1, 3, 3, 3, kInf};
  sim::FaultMonitor m(0.5, lower, upper);
  const fuzzypid::robot::JointVector ref{};
  EXPECT_FALSE(m.observe(0.0, ref, {0.5, 0, 0, 0, 0, 0}));  // |e| = 0.5 is not > 0.5
  EXPECT_TRUE(m.observe(0.1, ref, {0.6, 0, 0, 0, 0, 0}));
  EXPECT_TRUE(m.observe(0.2, ref, {0.7, 0, 0, 0, 0, 0}));
  // Joint 2 at 1.2 rad, the reference beside it: outside its limits, not diverged.
  const fuzzypid::robot::JointVector near_2{0, 1.0, 0, 0, 0, 100.0};
  EXPECT_TRUE(m.observe(0.3, near_2, {0, 1.2, 0, 0, 0, 100.0}));
  // NaN is a divergence.
  EXPECT_TRUE(m.observe(0.4, ref, {0, 0, std::nan(""), 0, 0, 0}));
  const sim::TrackingFaults& f = m.faults();
  EXPECT_EQ(f.ticks, 4u);
  EXPECT_EQ(f.divergence[0].ticks, 2u);
  EXPECT_DOUBLE_EQ(f.divergence[0].first_t_s, 0.1);
  EXPECT_DOUBLE_EQ(f.divergence[0].first_value_rad, 0.6);
  EXPECT_EQ(f.divergence[1].ticks, 0u);
  EXPECT_EQ(f.joint_limit[1].ticks, 1u);
  EXPECT_DOUBLE_EQ(f.joint_limit[1].first_value_rad, 1.2);
  EXPECT_EQ(f.divergence[2].ticks, 1u);
  EXPECT_EQ(f.joint_limit[5].ticks, 0u);  // continuous: 100 rad is no violation
  const std::vector<std::string> lines = sim::describe(f, 0.5, lower, upper);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "joint 1: |error| 0.6 rad > 0.5 rad at t = 0.1 s (first of 2 ticks)");
  EXPECT_EQ(lines[1],
            "joint 2: angle 1.2 rad outside its limits [-1, 1] rad at t = 0.3 s "
            "(first of 1 ticks)");
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
