// The tuner (fuzzypid/tune): the optimiser finds a brute-forced optimum, never exceeds its budget,
// and tuning is deterministic for a seed (and independent of the thread count).
#include <algorithm>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzzypid/controller/families.hpp"
#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid/pid/pid.hpp"
#include "fuzzypid/robot/path.hpp"
#include "fuzzypid/robot/robot_model.hpp"
#include "fuzzypid/sim/experiment.hpp"
#include "fuzzypid/sim/metrics.hpp"
#include "fuzzypid/tune/tune.hpp"

namespace {

namespace cf = fuzzypid::controller_file;
namespace controller = fuzzypid::controller;
namespace tune = fuzzypid::tune;

// The family a controller file calls `name` (the test fails for a name no family has).
controller::Family named_family(std::string_view name) {
  const std::optional<controller::Family> f = controller::parse_family(name);
  EXPECT_TRUE(f.has_value()) << name;
  return f.value_or(controller::Family{});
}

// ITAE of a unit double integrator (x'' = u, zero-order hold, exact discretisation at dt) under
// the library's PID with gains 10^x (continuous form), following a unit step for 8 s. Sampling
// makes large gains unstable, so the optimum lies inside the box.
double double_integrator_itae(const std::vector<double>& x) {
  constexpr double dt = 0.1;
  fuzzypid::pid::Config<double> c;
  c.gains = {std::pow(10.0, x[0]), std::pow(10.0, x[1]), std::pow(10.0, x[2])};
  fuzzypid::pid::Pid<double> pid(c);
  double pos = 0.0, vel = 0.0, itae = 0.0;
  for (int k = 0; k <= 80; ++k) {
    const double t = k * dt;
    const double e = 1.0 - pos;
    itae += t * std::fabs(e) * dt;
    if (std::fabs(e) > 10.0) return 1e3;  // diverged
    fuzzypid::pid::Input<double> in;
    in.setpoint = 1.0;
    in.measurement = pos;
    in.setpoint_rate = 0.0;
    in.measurement_rate = vel;
    (void)pid.update(in, dt);
    const double u = pid.output();
    pos += vel * dt + 0.5 * u * dt * dt;
    vel += u * dt;
  }
  return itae;
}

const std::vector<tune::SearchBox> kToyBox = {
    {"kp", -1.0, 2.0}, {"ki", -3.0, 1.0}, {"kd", -1.0, 2.0}};

TEST(OnBound, NamesEveryParameterWithinOnePercentOfASideOfItsBoxAndNoOther) {
  const std::vector<tune::SearchBox> box = {
      {"kp", 0.0, 4.0}, {"ki", -3.0, 1.0}, {"kd", 0.0, 4.0}, {"held", 2.0, 2.0}};
  // kp 0.96 % of the width below the top, ki 0.9 % above the bottom, kd 1.1 % below the top; a
  // parameter held fixed (zero width) is never on a bound.
  const auto hits = tune::on_bound({3.9616, -2.964, 3.956, 2.0}, box);
  ASSERT_EQ(hits.size(), 2u);
  EXPECT_EQ(hits[0].name, "kp");
  EXPECT_TRUE(hits[0].upper);
  EXPECT_DOUBLE_EQ(hits[0].log10, 3.9616);
  EXPECT_EQ(hits[1].name, "ki");
  EXPECT_FALSE(hits[1].upper);
  EXPECT_TRUE(tune::on_bound({2.0, -1.0, 2.0, 2.0}, box).empty());
}

// The derivative filter's bottom is its "off" end: a filter there is not a box too small. Its top
// is reported like any other parameter's.
TEST(OnBound, TheDerivativeFilterIsReportedOnlyAtTheTopOfItsBox) {
  const std::vector<tune::SearchBox> box = {{"kp", 0.0, 4.0}, {"tf", -3.0, 0.0}};
  EXPECT_TRUE(tune::on_bound({2.0, -3.0}, box).empty());
  const auto hits = tune::on_bound({2.0, 0.0}, box);
  ASSERT_EQ(hits.size(), 1u);
  EXPECT_EQ(hits[0].name, "tf");
  EXPECT_TRUE(hits[0].upper);
}

// The paper scenario with measurement noise: the command reverses on many ticks.
std::vector<fuzzypid::sim::Condition> noisy_condition() {
  std::vector<fuzzypid::sim::Condition> conditions(1);
  conditions[0].noise_position_rad = 1e-4;
  conditions[0].noise_velocity_rad_s = 1e-3;
  return conditions;
}

TEST(Objective, ChatterAndEffortTermsAreTheirWeightsTimesTheRunsSharesAndZeroByDefault) {
  std::string error;
  const auto ex = fuzzypid::sim::Experiment::create(fuzzypid::sim::RobotSetup{},
                                                    fuzzypid::sim::ExperimentOptions{}, error);
  ASSERT_TRUE(ex) << error;
  const auto conditions = noisy_condition();  // both terms non-zero
  const controller::ControllerSpec pid = controller::paper_pid();
  tune::Objective plain;
  EXPECT_EQ(plain.chatter_weight, 300.0);  // the defaults (docs/tuning.md, "Chatter")
  EXPECT_EQ(plain.chatter_limit_pct, 5.0);
  plain.chatter_weight = 0.0;
  plain.chatter_limit_pct = 0.0;  // every reversal costs: the closed form below
  const tune::Cost base = tune::evaluate(*ex, conditions, pid, plain);
  EXPECT_EQ(base.chatter_penalty, 0.0);
  EXPECT_EQ(base.effort_penalty, 0.0);
  tune::Objective drive = plain;
  drive.chatter_weight = 2.0;
  drive.effort_weight = 3.0;
  const tune::Cost c = tune::evaluate(*ex, conditions, pid, drive);
  // The same run: the same ITAE; the terms computed here from its rows.
  EXPECT_EQ(c.itae, base.itae);
  const auto run = ex->run(conditions[0], pid);
  const auto limit = ex->output_limit(conditions[0], pid.units.gains);
  double chatter = 0.0, effort = 0.0;
  const std::size_t ticks = run.rows.size() / 6;
  for (std::size_t j = 0; j < 6; ++j) {
    std::vector<double> u(ticks);
    double sq = 0.0;
    for (std::size_t k = 0; k < ticks; ++k) {
      u[k] = run.rows[k * 6 + j].u;
      sq += u[k] * u[k];
    }
    chatter += fuzzypid::sim::reversals_pct(u) / 100.0;
    effort += std::sqrt(sq / static_cast<double>(ticks)) / limit[j];
  }
  EXPECT_GT(effort, 0.0);
  EXPECT_GT(chatter, 0.1);
  EXPECT_DOUBLE_EQ(c.chatter_penalty, 2.0 * chatter);
  EXPECT_DOUBLE_EQ(c.effort_penalty, 3.0 * effort);
  EXPECT_DOUBLE_EQ(c.total, base.total + c.chatter_penalty + c.effort_penalty);
}

// --chatter-limit L: only each joint's share above L % costs (a hinge), so a run whose joints all
// reverse on fewer ticks costs nothing and one above pays only the excess.
TEST(Objective, ChatterLimitChargesOnlyTheShareAboveIt) {
  std::string error;
  const auto ex = fuzzypid::sim::Experiment::create(fuzzypid::sim::RobotSetup{},
                                                    fuzzypid::sim::ExperimentOptions{}, error);
  ASSERT_TRUE(ex) << error;
  const auto conditions = noisy_condition();
  const controller::ControllerSpec pid = controller::paper_pid();
  const auto run = ex->run(conditions[0], pid);
  const std::size_t ticks = run.rows.size() / 6;
  std::vector<double> share(6);
  for (std::size_t j = 0; j < 6; ++j) {
    std::vector<double> u(ticks);
    for (std::size_t k = 0; k < ticks; ++k)
      u[k] = run.rows[k * 6 + j].u;
    share[j] = fuzzypid::sim::reversals_pct(u);
  }
  const double lo = *std::min_element(share.begin(), share.end());
  const double hi = *std::max_element(share.begin(), share.end());
  ASSERT_LT(lo, hi);
  tune::Objective o;
  o.chatter_weight = 2.0;
  o.chatter_limit_pct = 0.5 * (lo + hi);  // some joints above, some below
  double excess = 0.0;
  for (double s : share)
    excess += std::max(0.0, s - o.chatter_limit_pct) / 100.0;
  EXPECT_GT(excess, 0.0);
  EXPECT_DOUBLE_EQ(tune::evaluate(*ex, conditions, pid, o).chatter_penalty, 2.0 * excess);
  o.chatter_limit_pct = hi;
  EXPECT_EQ(tune::evaluate(*ex, conditions, pid, o).chatter_penalty, 0.0);
}

TEST(Minimize, PidFamilyFindsTheBruteForcedItaeOptimumOfADoubleIntegrator) {
  // Brute force on a 61 x 41 x 61 grid (0.05 decade steps in kp and kd, 0.1 in ki).
  std::vector<double> best_x;
  double best = 1e300;
  for (int i = 0; i <= 60; ++i)
    for (int j = 0; j <= 40; ++j)
      for (int k = 0; k <= 60; ++k) {
        const std::vector<double> x = {-1.0 + 0.05 * i, -3.0 + 0.1 * j, -1.0 + 0.05 * k};
        const double f = double_integrator_itae(x);
        if (f < best) {
          best = f;
          best_x = x;
        }
      }
  tune::MinimizeOptions o;
  o.budget = 3000;
  o.seed = 1;
  std::string error;
  const auto m = tune::minimize(double_integrator_itae, kToyBox, o, error);
  ASSERT_TRUE(m) << error;
  // At least as good as the grid (to 0.5 %), at the grid optimum's gains (to one grid step).
  EXPECT_LE(m->f, best * 1.005);
  EXPECT_NEAR(m->x[0], best_x[0], 0.05);
  EXPECT_NEAR(m->x[2], best_x[2], 0.05);
}

TEST(Minimize, NeverExceedsTheBudgetAndSpendsWholeGenerations) {
  for (const std::uint64_t budget : {40u, 41u, 59u, 100u, 257u}) {
    std::uint64_t calls = 0;
    const auto f = [&calls](const std::vector<double>& x) {
      ++calls;
      return double_integrator_itae(x);
    };
    tune::MinimizeOptions o;
    o.budget = budget;
    o.population = 20;
    std::string error;
    const auto m = tune::minimize(f, kToyBox, o, error);
    ASSERT_TRUE(m) << error;
    EXPECT_LE(calls, budget);
    EXPECT_EQ(m->evaluations, calls);
    EXPECT_EQ(calls, budget / 20 * 20);  // the initial population plus whole generations
  }
}

TEST(Minimize, RejectsABudgetBelowTwoGenerations) {
  tune::MinimizeOptions o;
  o.budget = 39;
  o.population = 20;
  std::string error;
  EXPECT_FALSE(tune::minimize(double_integrator_itae, kToyBox, o, error));
  EXPECT_NE(error.find("budget"), std::string::npos);
}

class TuneOnTheRobot : public ::testing::Test {
 protected:
  void SetUp() override {
    auto loaded = fuzzypid::robot::RobotModel::load(fuzzypid::robot::default_urdf_path());
    ASSERT_TRUE(loaded.model) << loaded.error;
    model_ = std::move(loaded.model);
    std::string error;
    fuzzypid::sim::ExperimentOptions options;
    options.plant.armature_kgm2 = fuzzypid::robot::kEr50ArmatureKgm2;  // the bundled ER50-C20's
    experiment_ = fuzzypid::sim::Experiment::create(*model_, fuzzypid::robot::paper_path_spec(),
                                                    options, error);
    ASSERT_TRUE(experiment_) << error;
    fuzzypid::sim::Condition behind, ahead;
    behind.name = "behind";
    ahead.name = "ahead";
    ahead.initial_error_rad = -0.05;
    ahead.payload_scale = 2.0;
    training_ = {behind, ahead};
  }

  std::string tuned(controller::Family family, unsigned threads, std::uint64_t seed) {
    tune::Options o;
    o.family = family;
    o.budget = 60;
    o.population = 20;
    o.seed = seed;
    o.threads = threads;
    std::string error;
    auto r = tune::tune(*experiment_, training_, o, error);
    EXPECT_TRUE(r) << error;
    if (!r) return {};
    EXPECT_LE(r->evaluations, 60u);
    return cf::to_toml(cf::ControllerFile{r->controller, r->tuning, std::nullopt});
  }

  std::optional<fuzzypid::robot::RobotModel> model_;
  std::optional<fuzzypid::sim::Experiment> experiment_;
  std::vector<fuzzypid::sim::Condition> training_;
};

TEST_F(TuneOnTheRobot, TheSameSeedGivesTheSameFileWithAnyThreadCount) {
  for (const controller::Family f : {named_family("pid"), named_family("scheduled"),
                                     named_family("fuzzy"), named_family("fuzzy-rules")}) {
    const std::string a = tuned(f, 1, 5);
    EXPECT_EQ(a, tuned(f, 1, 5));
    EXPECT_EQ(a, tuned(f, 2, 5));
    EXPECT_NE(a, tuned(f, 1, 6));
  }
}

TEST_F(TuneOnTheRobot, TheRecordedCostIsTheObjectiveOfTheResult) {
  tune::Options o;
  o.family = named_family("fuzzy");
  o.budget = 60;
  o.population = 20;
  std::string error;
  const auto r = tune::tune(*experiment_, training_, o, error);
  ASSERT_TRUE(r) << error;
  const tune::Cost c = tune::evaluate(*experiment_, training_, r->controller, o.objective, 1);
  EXPECT_EQ(c.total, r->tuning.training_cost);
  EXPECT_EQ(c.total, r->cost.total);
}

// Tuning pays for itself: at a small budget every family ends below the training cost of the
// controller it starts from (the paper's gains, the base's units): at half of it on tracking
// alone, and below it with the default objective, whose chatter term the paper's gains barely
// pay on this rigid plant.
TEST_F(TuneOnTheRobot, TuningLowersTheTrainingCostBelowThePapersControllers) {
  for (const double chatter_weight : {0.0, tune::Objective{}.chatter_weight}) {
    tune::Options o;
    o.budget = 200;
    o.population = 20;
    o.objective.chatter_weight = chatter_weight;
    const double factor = chatter_weight == 0.0 ? 0.5 : 1.0;
    const double paper_pid =
        tune::evaluate(*experiment_, training_, controller::paper_pid(), o.objective, 1).total;
    const double paper_fuzzy =
        tune::evaluate(*experiment_, training_, controller::paper_fuzzy(), o.objective, 1).total;
    for (const controller::Family f :
         {named_family("pid"), named_family("scheduled"), named_family("fuzzy")}) {
      o.family = f;
      std::string error;
      const auto r = tune::tune(*experiment_, training_, o, error);
      ASSERT_TRUE(r) << error;
      EXPECT_LT(r->cost.total, factor * std::min(paper_pid, paper_fuzzy))
          << controller::to_string(f) << ", chatter weight " << chatter_weight;
    }
  }
}

// Staged tuning with a validation split: each stage starts from the last one's result, the budgets
// add up, the held-back conditions are never trained on, and the file is the same whatever the
// thread count.
class StagedTuning : public TuneOnTheRobot {
 protected:
  void SetUp() override {
    TuneOnTheRobot::SetUp();
    fuzzypid::sim::Condition held;
    held.name = "held";
    held.payload_scale = 1.3;
    held.initial_error_rad = 0.03;
    conditions_ = training_;
    conditions_.push_back(held);
    std::string error;
    set_ = fuzzypid::sim::ExperimentSet::create(conditions_, {}, error);
    ASSERT_TRUE(set_) << error;
  }

  std::optional<tune::Result> staged(unsigned threads) {
    tune::Options o;
    o.seed = 3;
    o.threads = threads;
    o.population = 20;
    o.validation = 1;
    std::string error;
    auto r = tune::tune_staged(*set_, conditions_, stages_, o, error);
    EXPECT_TRUE(r) << error;
    return r;
  }

  std::vector<fuzzypid::sim::Condition> conditions_;
  std::optional<fuzzypid::sim::ExperimentSet> set_;
  std::vector<tune::Stage> stages_ = {{named_family("pid"), 100},
                                      {named_family("scheduled"), 100},
                                      {named_family("fuzzy-rules"), 120}};
};

TEST_F(StagedTuning, StagesAddUpAndTheResultIsTheLastFamilysAtAnyThreadCount) {
  auto a = staged(1);
  auto b = staged(2);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->controller.family, named_family("fuzzy-rules"));
  const tune::Tuning& t = a->tuning;
  ASSERT_EQ(t.stages.size(), 3u);
  EXPECT_EQ(t.budget, 320u);
  EXPECT_EQ(t.evaluations,
            t.stages[0].evaluations + t.stages[1].evaluations + t.stages[2].evaluations);
  EXPECT_LE(t.evaluations, 320u);
  EXPECT_EQ(t.validation_conditions, 1u);
  EXPECT_EQ(cf::to_toml(cf::ControllerFile{a->controller, a->tuning, std::nullopt}),
            cf::to_toml(cf::ControllerFile{b->controller, b->tuning, std::nullopt}));
}

TEST_F(StagedTuning, EveryStageStartsWhereTheLastEndedAndNeverEndsAbove) {
  auto r = staged(2);
  ASSERT_TRUE(r);
  const auto& st = r->tuning.stages;
  // The start is a member of each stage's first generation and conversions are exact: the
  // training cost of a stage's champion never rises above the last stage's (to rounding).
  EXPECT_LE(st[1].training_cost, st[0].training_cost * (1 + 1e-9));
  EXPECT_LE(st[2].training_cost, st[1].training_cost * (1 + 1e-9));
}

TEST_F(StagedTuning, TheHeldBackConditionsAreScoredNotTrainedOn) {
  auto r = staged(2);
  ASSERT_TRUE(r);
  const tune::Objective o;
  const std::vector<fuzzypid::sim::Condition> held = {conditions_.back()};
  const auto& setup = *set_;
  const double validation = tune::evaluate(setup.of(2), held, r->controller, o, 1).total;
  EXPECT_EQ(validation, r->tuning.validation_cost);
  const double training = tune::evaluate(*experiment_, training_, r->controller, o, 1).total;
  EXPECT_EQ(training + r->penalty, r->tuning.training_cost);
  EXPECT_NE(validation, training);
}

TEST_F(StagedTuning, AStartFromAFamilyWithoutAnExactFormIsRefused) {
  tune::Options o;
  o.population = 20;
  o.init = controller::paper_fuzzy();
  o.family = named_family("scheduled");
  o.budget = 60;
  std::string error;
  EXPECT_FALSE(tune::tune(*set_, conditions_, o, error));
  EXPECT_NE(error.find("no exact"), std::string::npos);
  o.validation = conditions_.size();
  o.init.reset();
  EXPECT_FALSE(tune::tune(*set_, conditions_, o, error));
  EXPECT_NE(error.find("no training conditions"), std::string::npos);
}

// The default condition on the ER50-C20 and on the UR5-class arm following its contour.
std::vector<fuzzypid::sim::Condition> er50_and_ur5() {
  fuzzypid::sim::Condition er50, ur5;
  er50.name = "er50";
  ur5.name = "ur5";
  ur5.robot.urdf = FUZZYPID_SOURCE_DIR "/urdf/ur5_class.urdf";
  ur5.robot.path = FUZZYPID_SOURCE_DIR "/paths/ur5_deburring_contour.csv";
  ur5.robot.armature_kgm2 = fuzzypid::robot::JointVector{0.4, 0.4, 0.4, 0.1, 0.1, 0.1};
  return {er50, ur5};
}

// Each training condition runs on its own robot: a set of two arms tunes, and its cost is the
// sum of each arm's own cost.
TEST(TuneOnTwoRobots, EachConditionRunsOnItsOwnExperiment) {
  const std::vector<fuzzypid::sim::Condition> both = er50_and_ur5();
  const fuzzypid::sim::Condition& er50 = both[0];
  const fuzzypid::sim::Condition& ur5 = both[1];
  std::string error;
  const auto set = fuzzypid::sim::ExperimentSet::create(both, {}, error);
  ASSERT_TRUE(set) << error;
  ASSERT_EQ(set->size(), 2u);
  const controller::ControllerSpec pid = controller::paper_pid();
  const tune::Objective objective;
  const double sum = tune::evaluate(*set, both, pid, objective, 2).total;
  const double a = tune::evaluate(set->of(0), {er50}, pid, objective, 1).total;
  const double b = tune::evaluate(set->of(1), {ur5}, pid, objective, 1).total;
  EXPECT_DOUBLE_EQ(sum, a + b);
  EXPECT_NE(a, b);
}

// The held-back conditions run on their own robots too: training on the ER50-C20, validation on
// the UR5-class arm, the recorded validation cost is the result's cost on the UR5 (a split that
// paired the validation conditions with the training experiments would score it on the ER50).
TEST(TuneOnTwoRobots, ValidationConditionsRunOnTheirOwnExperiment) {
  const std::vector<fuzzypid::sim::Condition> both = er50_and_ur5();
  const fuzzypid::sim::Condition& er50 = both[0];
  const fuzzypid::sim::Condition& ur5 = both[1];
  std::string error;
  const auto set = fuzzypid::sim::ExperimentSet::create(both, {}, error);
  ASSERT_TRUE(set) << error;
  tune::Options o;
  o.family = named_family("pid");
  o.budget = 14;
  o.population = 7;
  o.validation = 1;
  const auto r = tune::tune(*set, both, o, error);
  ASSERT_TRUE(r) << error;
  ASSERT_TRUE(r->validation);
  const double on_ur5 = tune::evaluate(set->of(1), {ur5}, r->controller, o.objective, 1).total;
  EXPECT_EQ(r->tuning.validation_cost, on_ur5);
  EXPECT_EQ(r->tuning.validation_conditions, 1u);
  const double on_er50 = tune::evaluate(set->of(0), {er50}, r->controller, o.objective, 1).total;
  EXPECT_EQ(r->tuning.training_cost, on_er50 + r->penalty);
}

}  // namespace
