// sim::run_sweep (sim/sweep.hpp), the robustness sweep of sim_ab --sweep: the values it steps,
// the parameter it changes, what it calls usable, and the longest usable stretch it reports.
#include "fuzzypid/sim/sweep.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "fuzzypid/controller/families.hpp"
#include "fuzzypid/robot/path.hpp"
#include "fuzzypid/robot/robot_model.hpp"
#include "fuzzypid/sim/condition.hpp"
#include "fuzzypid/sim/experiment.hpp"

namespace {

using namespace fuzzypid;

TEST(LongestTrueStretch, IsTheFirstOfTheLongestRuns) {
  using Result = std::array<std::size_t, 2>;
  EXPECT_EQ(sim::longest_true_stretch({}), (Result{0, 0}));
  EXPECT_EQ(sim::longest_true_stretch({false, false}), (Result{0, 0}));
  EXPECT_EQ(sim::longest_true_stretch({true}), (Result{0, 1}));
  EXPECT_EQ(sim::longest_true_stretch({false, true, true, false, true, true, true}),
            (Result{4, 3}));
  EXPECT_EQ(sim::longest_true_stretch({true, true, false, true, true}), (Result{0, 2}));
  EXPECT_EQ(sim::longest_true_stretch({false, true, true, true, true}), (Result{1, 4}));
}

TEST(Sweep, StepsEvenlyFromLoToHiAndSetsOnlyItsParameter) {
  const sim::Sweep sw{sim::SweepParameter::TorqueLimit, 2.0, 4.0, 5};
  EXPECT_EQ(sw.value(0), 2.0);
  EXPECT_EQ(sw.value(2), 3.0);
  EXPECT_EQ(sw.value(4), 4.0);
  EXPECT_EQ((sim::Sweep{sim::SweepParameter::PayloadScale, 1.5, 1.5, 1}.value(0)), 1.5);

  const sim::Condition base = *sim::find_scenario("paper");
  const sim::Condition torque = sw.at(base, 3.0);
  EXPECT_EQ(torque.torque_limit_rad_s2, 3.0);
  EXPECT_EQ(torque.payload_scale, base.payload_scale);
  const sim::Condition payload =
      sim::Sweep{sim::SweepParameter::PayloadScale, 0.5, 2.0, 4}.at(base, 2.0);
  EXPECT_EQ(payload.payload_scale, 2.0);
  EXPECT_EQ(payload.torque_limit_rad_s2, base.torque_limit_rad_s2);
}

class RunSweep : public ::testing::Test {
 protected:
  void SetUp() override {
    auto loaded = robot::RobotModel::load(robot::default_urdf_path());
    ASSERT_TRUE(loaded.model) << loaded.error;
    model_ = std::move(loaded.model);
    std::string error;
    experiment_ = sim::Experiment::create(*model_, robot::paper_path_spec(), {}, error);
    ASSERT_TRUE(experiment_) << error;
    spec_ = sim::default_controller(experiment_->options(), controller::paper_pid());
  }
  std::optional<robot::RobotModel> model_;
  std::optional<sim::Experiment> experiment_;
  controller::ControllerSpec spec_;
  sim::Condition base_ = *sim::find_scenario("paper");
};

TEST_F(RunSweep, TheNominalValueReproducesTheNominalRun) {
  // One value, the base condition's own payload scale: the same run as the nominal one.
  const sim::Sweep sw{sim::SweepParameter::PayloadScale, base_.payload_scale, base_.payload_scale,
                      1};
  sim::SweepBounds bounds;
  bounds.overshoot_pct = 1e9;
  const sim::SweepResult r = sim::run_sweep(*experiment_, base_, spec_, sw, bounds);
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.points.size(), 1u);
  EXPECT_GT(r.nominal_itae, 0.0);
  EXPECT_EQ(r.points[0].itae, r.nominal_itae);
  EXPECT_TRUE(r.points[0].usable);
  EXPECT_EQ(r.usable_first, 0u);
  EXPECT_EQ(r.usable_count, 1u);

  // The ITAE bound is relative to the nominal run: half of it refuses the nominal run itself.
  bounds.itae_ratio = 0.5;
  const sim::SweepResult strict = sim::run_sweep(*experiment_, base_, spec_, sw, bounds);
  ASSERT_TRUE(strict.ok) << strict.error;
  EXPECT_FALSE(strict.points[0].usable);
  EXPECT_EQ(strict.usable_count, 0u);
}

TEST_F(RunSweep, AHeavierPayloadRaisesTheItaeAndTheStretchFollowsTheBound) {
  const sim::Sweep sw{sim::SweepParameter::PayloadScale, 1.0, 4.0, 4};
  sim::SweepBounds bounds;
  bounds.overshoot_pct = 1e9;
  const sim::SweepResult loose = sim::run_sweep(*experiment_, base_, spec_, sw, bounds);
  ASSERT_TRUE(loose.ok) << loose.error;
  ASSERT_EQ(loose.points.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k)
    EXPECT_EQ(loose.points[k].value, 1.0 + static_cast<double>(k));
  EXPECT_GT(loose.points[3].itae, loose.points[0].itae);
  // A bound between the first two values' ITAE ratios keeps only the first value.
  const double r1 = loose.points[1].itae / loose.nominal_itae;
  const double r0 = loose.points[0].itae / loose.nominal_itae;
  ASSERT_GT(r1, r0);
  bounds.itae_ratio = 0.5 * (r0 + r1);
  const sim::SweepResult tight = sim::run_sweep(*experiment_, base_, spec_, sw, bounds);
  ASSERT_TRUE(tight.ok) << tight.error;
  EXPECT_TRUE(tight.points[0].usable);
  EXPECT_FALSE(tight.points[1].usable);
  EXPECT_EQ(tight.usable_first, 0u);
  EXPECT_EQ(tight.usable_count, 1u);
}

TEST_F(RunSweep, ARunPastTheDivergenceBoundIsDivergedAndNamesItsFault) {
  const sim::Sweep sw{sim::SweepParameter::TorqueLimit, 1.0, 1.0, 1};
  sim::SweepBounds bounds;
  bounds.divergence_rad = 1e-9;  // the paper's start error is far beyond it
  const sim::SweepResult r = sim::run_sweep(*experiment_, base_, spec_, sw, bounds);
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.points.size(), 1u);
  const sim::SweepPoint& p = r.points[0];
  EXPECT_TRUE(p.diverged);
  EXPECT_TRUE(std::isinf(p.itae));
  EXPECT_TRUE(std::isinf(p.max_overshoot_pct));
  EXPECT_GT(p.fault_ticks, 0u);
  EXPECT_FALSE(p.usable);
  EXPECT_NE(p.first_fault.find("rad"), std::string::npos) << p.first_fault;
  EXPECT_EQ(r.usable_count, 0u);
}

}  // namespace
