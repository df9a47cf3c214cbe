// fuzzy::evaluate and fuzzy::Engine on hand-built models: the weighted average, refused inputs,
// lock-previous in the workspace, chained antecedents (the file-level and fuzzylite comparisons
// are in test_rule_file_constructs.cpp and tests/rulefile/test_corpus.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "engine_test_models.hpp"
#include "fuzzypid/fuzzy/engine.hpp"

namespace {

using fuzzypid::Status;
using fuzzypid::fuzzy::DynamicWorkspace;
using Engine = fuzzypid::fuzzy::Engine<double, fuzzypid::fuzzy::FixedCapacity>;
using fuzzypid::fuzzy::Token;
using fuzzypid::test::conclusion;
using fuzzypid::test::proposition;
using fuzzypid::test::ramp_model;

TEST(EngineEvaluate, WeightedAverageOfTheFiredConstants) {
  const auto model = ramp_model();
  auto engine = std::make_unique<Engine>(*model);
  const double x = 0.25;  // lo 0.75, hi 0.25
  double y = 0;
  ASSERT_EQ(engine->evaluate(&x, &y), Status::Ok);
  EXPECT_EQ(y, (0.75 * 1 + 0.25 * 3) / 1.0);
  EXPECT_EQ(engine->rule_strength(0), 0.75);
}

TEST(EngineEvaluate, ANonFiniteInputIsRefusedWithZeroOutputs) {
  const auto model = ramp_model();
  auto engine = std::make_unique<Engine>(*model);
  const double x = std::numeric_limits<double>::quiet_NaN();
  double y = 7;
  EXPECT_EQ(engine->evaluate(&x, &y), Status::NonFiniteInput);
  EXPECT_EQ(y, 0.0);
}

TEST(EngineEvaluate, LockPreviousKeepsTheLastFiniteValueOfThatWorkspace) {
  auto model = ramp_model();
  model->inputs[0].terms[1].p = {0.5, 1, 0, 0};  // hi: 0 below 0.5
  model->rules[0].weight = 0.0;                  // only "hi" can fire
  model->outputs[0].lock_previous = true;
  DynamicWorkspace<double> a(*model), b(*model);
  double y = 0;
  const double high = 1.0, low = 0.2;
  EXPECT_EQ(fuzzypid::fuzzy::evaluate(*model, a.view(), &high, &y), Status::Ok);
  EXPECT_EQ(y, 3.0);
  EXPECT_EQ(fuzzypid::fuzzy::evaluate(*model, a.view(), &low, &y), Status::Ok);
  EXPECT_EQ(y, 3.0);  // held
  EXPECT_EQ(fuzzypid::fuzzy::evaluate(*model, b.view(), &low, &y), Status::NoRuleFired);
  EXPECT_EQ(y, 0.0);  // another workspace holds nothing yet
}

TEST(EngineEvaluate, AChainedRuleSeesOnlyConclusionsTriggeredBeforeIt) {
  auto model = ramp_model(true);
  // "if y is three then z is ten" twice: before and after the rules on y. With General
  // activation the first reads 0 and does not fire; the last reads hi's degree.
  const Token on_y = proposition(0, 1, Token::Kind::OutputProposition);
  const auto to_z = conclusion(1, 0);
  auto chained = std::make_unique<fuzzypid::test::Model>();
  *chained = *model;
  chained->num_rules = chained->num_tokens = chained->num_conclusions = 0;
  ASSERT_TRUE(chained->add_rule(&on_y, 1, &to_z, 1));
  for (std::uint8_t t = 0; t < 2; ++t) {
    const Token a = proposition(0, t);
    const auto c = conclusion(0, t);
    ASSERT_TRUE(chained->add_rule(&a, 1, &c, 1));
  }
  ASSERT_TRUE(chained->add_rule(&on_y, 1, &to_z, 1, 0.5));
  ASSERT_FALSE(fuzzypid::fuzzy::validate(*chained));
  auto engine = std::make_unique<Engine>(*chained);
  const double x = 0.75;
  double out[2] = {};
  ASSERT_EQ(engine->evaluate(&x, out), Status::Ok);
  EXPECT_EQ(engine->rule_strength(0), 0.0);
  EXPECT_EQ(engine->rule_strength(3), 0.5 * 0.75);
  EXPECT_EQ(out[1], 10.0);
}

}  // namespace
