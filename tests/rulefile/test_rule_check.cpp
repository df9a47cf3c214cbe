// rulefile::check_rules as a specification: coverage gaps as boxes of grid points, repeated and
// contradictory rules, monotonicity of each output in each input.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "fuzzypid/rulefile/rule_check.hpp"
#include "fuzzypid/rulefile/rule_file.hpp"

namespace {

using fuzzypid::rulefile::Model;
using fuzzypid::rulefile::Monotonicity;
using fuzzypid::rulefile::RuleCheckOptions;

std::unique_ptr<Model> fll(const std::string& text) {
  auto model = std::make_unique<Model>();
  fuzzypid::rulefile::LoadError error;
  EXPECT_TRUE(fuzzypid::rulefile::parse_fll(text, "check.fll", *model, error)) << error.to_string();
  return model;
}

// x on [0, 1] with a gap between `low` and `high`; z on [0, 1] fully covered by `any`.
const std::string kTwoInputs = R"(Engine: gap2
InputVariable: x
  range: 0 1
  term: low Trapezoid -1 -1 0.3 0.4
  term: high Trapezoid 0.6 0.7 2 2
InputVariable: z
  range: 0 1
  term: all Trapezoid -1 -1 2 2
OutputVariable: y
  range: 0 10
  aggregation: none
  defuzzifier: WeightedAverage TakagiSugeno
  default: nan
  term: a Constant 1
  term: b Constant 5
  term: c Linear 0 -4 9
RuleBlock: rules
  conjunction: Minimum
  activation: General
  rule: if x is low and z is all then y is a
  rule: if x is high then y is b
  rule: if z is all and x is low then y is a
)";

TEST(RuleCheck, AGapIsABoxOfGridPointsWithItsCoordinatesAndOutputs) {
  const auto model = fll(kTwoInputs);
  RuleCheckOptions options;
  options.points_per_input = 11;
  const auto report = fuzzypid::rulefile::check_rules(*model, options);
  EXPECT_EQ(report.grid_points, 121u);
  ASSERT_EQ(report.gaps.size(), 1u);
  const auto& gap = report.gaps[0];
  EXPECT_EQ(gap.min[0], 0.4);  // low is 0 from 0.4, high from 0.6 (grid points 0.4, 0.5, 0.6)
  EXPECT_EQ(gap.max[0], 0.6);
  EXPECT_EQ(gap.min[1], 0.0);
  EXPECT_EQ(gap.max[1], 1.0);
  EXPECT_EQ(gap.points, 3u * 11u);
  EXPECT_EQ(gap.example[0], 0.5);
  ASSERT_EQ(gap.outputs.size(), 1u);
  EXPECT_EQ(gap.outputs[0], 0u);
  const std::string text = fuzzypid::rulefile::to_text(*model, report);
  EXPECT_NE(text.find("gap 1: x in [0.4, 0.6], z in [0, 1] (33 grid point(s), e.g. x = 0.5, z ="),
            std::string::npos)
      << text;
}

TEST(RuleCheck, RulesWithTheSameAntecedentInAnyOrderRepeatOrContradict) {
  std::string text = kTwoInputs + "  rule: if x is high then y is c\n";
  const auto model = fll(text);
  const auto report = fuzzypid::rulefile::check_rules(*model);
  ASSERT_EQ(report.pairs.size(), 2u);
  EXPECT_EQ(report.pairs[0].first, 0u);  // "x is low and z is all" = "z is all and x is low"
  EXPECT_EQ(report.pairs[0].second, 2u);
  EXPECT_FALSE(report.pairs[0].contradiction);
  EXPECT_EQ(report.pairs[1].first, 1u);
  EXPECT_EQ(report.pairs[1].second, 3u);
  EXPECT_TRUE(report.pairs[1].contradiction);
  const std::string out = fuzzypid::rulefile::to_text(*model, report);
  EXPECT_NE(out.find("rules: 1 repeated pair(s), 1 contradictory pair(s)"), std::string::npos)
      << out;
}

TEST(RuleCheck, AHedgeMakesAnotherPropositionAndAnotherConclusion) {
  const auto model = fll(R"(Engine: hedged
InputVariable: x
  range: 0 1
  term: low Triangle 0 0 1
  term: high Triangle 0 1 1
OutputVariable: y
  range: 0 1
  aggregation: Maximum
  defuzzifier: Centroid 100
  default: nan
  term: small Triangle 0 0 1
  term: big Triangle 0 1 1
RuleBlock: rules
  conjunction: Minimum
  implication: Minimum
  activation: General
  rule: if x is low then y is small
  rule: if x is very low then y is big
  rule: if x is high then y is big
  rule: if x is high then y is very big
  rule: if x is high then y is big
)");
  const auto report = fuzzypid::rulefile::check_rules(*model);
  // "x is very low" is not "x is low": rules 0 and 1 are no pair. "y is very big" is not "y is
  // big": rule 3 contradicts rules 2 and 4, which repeat each other.
  ASSERT_EQ(report.pairs.size(), 3u);
  EXPECT_EQ(report.pairs[0].first, 2u);
  EXPECT_EQ(report.pairs[0].second, 3u);
  EXPECT_TRUE(report.pairs[0].contradiction);
  EXPECT_EQ(report.pairs[1].first, 2u);
  EXPECT_EQ(report.pairs[1].second, 4u);
  EXPECT_FALSE(report.pairs[1].contradiction);
  EXPECT_EQ(report.pairs[2].first, 3u);
  EXPECT_EQ(report.pairs[2].second, 4u);
  EXPECT_TRUE(report.pairs[2].contradiction);
}

TEST(RuleCheck, MonotonicityIsJudgedAcrossGapsAlongEachInput) {
  const auto model = fll(kTwoInputs);
  const auto report = fuzzypid::rulefile::check_rules(*model);
  ASSERT_EQ(report.monotonicity.size(), 2u);
  EXPECT_EQ(report.monotonicity[0].kind, Monotonicity::Increasing);  // 1 below the gap, 5 above
  EXPECT_EQ(report.monotonicity[1].kind, Monotonicity::Constant);
  // y = 9 - 4 z above the gap: decreasing in z there, constant below.
  const auto linear = fll([] {
    std::string t = kTwoInputs;
    t.replace(t.find("then y is b"), 11, "then y is c");
    return t;
  }());
  const auto r2 = fuzzypid::rulefile::check_rules(*linear);
  EXPECT_EQ(r2.monotonicity[1].kind, Monotonicity::Decreasing);
  // Along x, y rises from 1 below the gap to 9 - 4 z >= 5 above it.
  EXPECT_EQ(r2.monotonicity[0].kind, Monotonicity::Increasing);
}

TEST(RuleCheck, AnOutputThatRisesAndFallsIsNotMonotoneWithBothPlaces) {
  std::string text = kTwoInputs;
  text.replace(text.find("term: a Constant 1"), 18, "term: a Constant 7");
  text.replace(text.find("rule: if x is high then y is b"), 30,
               "rule: if x is high then y is b\n  rule: if x is very high then y is a");
  const auto model = fll(text);
  const auto report = fuzzypid::rulefile::check_rules(*model);
  const auto& f = report.monotonicity[0];
  EXPECT_EQ(f.kind, Monotonicity::NotMonotone);
  ASSERT_EQ(f.fall_at.size(), 2u);
  ASSERT_EQ(f.rise_at.size(), 2u);
}

}  // namespace
