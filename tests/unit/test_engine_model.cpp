// fuzzy::EngineModel as a specification: what add_rule stores and refuses, and what validate()
// finds (the readers place its findings on file lines; here the model is built by hand).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "engine_test_models.hpp"
#include "fuzzypid/fuzzy/engine_model.hpp"
#include "fuzzypid/fuzzy/engine_model_validation.hpp"

namespace {

using fuzzypid::fuzzy::ModelError;
using fuzzypid::fuzzy::Token;
using fuzzypid::fuzzy::validate;
using fuzzypid::test::conclusion;
using fuzzypid::test::proposition;
using fuzzypid::test::ramp_model;

bool says(const ModelError& e, const char* text) {
  return e && std::string(e.message).find(text) != std::string::npos;
}

TEST(EngineModel, AHandBuiltModelIsValid) {
  EXPECT_FALSE(validate(*ramp_model()));
}

TEST(EngineModel, AddRuleRefusesAnAntecedentLongerThanTheCapacityAndLeavesTheModel) {
  auto m = ramp_model();
  Token tokens[64];
  for (auto& t : tokens)
    t = proposition(0, 0);
  const auto c = conclusion(0, 0);
  EXPECT_FALSE(m->add_rule(tokens, 64, &c, 1));
  EXPECT_EQ(m->num_rules, 2u);
  EXPECT_FALSE(validate(*m));
}

TEST(EngineModel, AnOutputPropositionMarksTheModelChainedAndNamesAKnownOutputTerm) {
  auto m = ramp_model(true);
  EXPECT_FALSE(m->chained);
  const Token on_output = proposition(0, 1, Token::Kind::OutputProposition);
  const auto c = conclusion(1, 0);
  ASSERT_TRUE(m->add_rule(&on_output, 1, &c, 1));
  EXPECT_TRUE(m->chained);
  EXPECT_FALSE(validate(*m));
  m->tokens[m->rules[2].first_token].term = 2;  // y has two terms
  EXPECT_TRUE(says(validate(*m), "unknown output term in its antecedent"));
  m->tokens[m->rules[2].first_token].term = 1;
  m->chained = false;  // a model edited by hand without the flag
  EXPECT_TRUE(says(validate(*m), "unknown output in its antecedent"));
}

// Octave's power hedges (a .fis code .dd) mark the model, so that evaluation takes the instance
// that computes them; a conclusion may hold one on a Sugeno output only.
TEST(EngineModel, APowerHedgeMarksTheModelAndConcludesOnSugenoOutputsOnly) {
  auto m = ramp_model();
  EXPECT_FALSE(m->power_hedges);
  Token cubed = proposition(0, 1);
  cubed.power_tenths = 30;
  auto rooted = conclusion(0, 0);
  rooted.power_tenths = 20;
  ASSERT_TRUE(m->add_rule(&cubed, 1, &rooted, 1));
  EXPECT_TRUE(m->power_hedges);
  EXPECT_FALSE(validate(*m));
  m->power_hedges = false;  // a model edited by hand without the flag
  EXPECT_TRUE(says(validate(*m), "with power_hedges set"));
  m->power_hedges = true;
  m->tokens[m->rules[2].first_token].power_tenths = 101;
  EXPECT_TRUE(says(validate(*m), "a power hedge must be .01 to 1.00"));
  m->tokens[m->rules[2].first_token].power_tenths = 30;
  auto& y = m->outputs[0];  // made a Mamdani output
  y.defuzzifier = fuzzypid::fuzzy::Defuzzifier::Centroid;
  y.min = 0;
  y.max = 4;
  for (std::size_t t = 0; t < 2; ++t) {
    y.terms[t].kind = fuzzypid::fuzzy::OutputTermKind::Membership;
    y.terms[t].membership = fuzzypid::fuzzy::Term<double>::triangle(0.0, 1.0 + t, 4.0);
  }
  EXPECT_TRUE(says(validate(*m), "concludes on Sugeno outputs only"));
  m->conclusions[m->rules[2].first_conclusion].power_tenths = 0;
  EXPECT_FALSE(validate(*m));
}

TEST(EngineModel, AZeroWidthRangeIsValidOnlyWhereNothingReadsIt) {
  auto m = ramp_model();
  m->outputs[0].min = m->outputs[0].max = 0.0;
  EXPECT_FALSE(validate(*m));  // weighted average over constants: the range is unused
  m->outputs[0].lock_range = true;
  EXPECT_TRUE(says(validate(*m), "output range"));
  m->outputs[0].lock_range = false;
  m->outputs[0].min = 1.0;  // inverted
  EXPECT_TRUE(says(validate(*m), "output range"));
}

TEST(EngineModel, TsukamotoTermsMustBeMonotonicConcaveIncluded) {
  auto m = ramp_model();
  for (std::size_t t = 0; t < 2; ++t) {
    auto& term = m->outputs[0].terms[t];
    term.kind = fuzzypid::fuzzy::OutputTermKind::Membership;
    term.membership.shape = fuzzypid::fuzzy::Shape::Concave;
    term.membership.p = {0.2, 0.6, 0, 0};
  }
  EXPECT_FALSE(validate(*m));
  m->outputs[0].terms[1].membership.shape = fuzzypid::fuzzy::Shape::Triangle;
  m->outputs[0].terms[1].membership.p = {0, 0.5, 1, 0};
  EXPECT_TRUE(says(validate(*m), "Tsukamoto terms must be"));
}

TEST(EngineModel, AnAndInABlockWithoutConjunctionIsFound) {
  auto m = ramp_model();
  const Token both[3] = {proposition(0, 0), proposition(0, 1), [] {
                           Token t;
                           t.kind = Token::Kind::And;
                           return t;
                         }()};
  const auto c = conclusion(0, 0);
  ASSERT_TRUE(m->add_rule(both, 3, &c, 1));
  EXPECT_FALSE(validate(*m));
  m->blocks[0].has_conjunction = false;
  const ModelError e = validate(*m);
  EXPECT_TRUE(says(e, "no conjunction"));
  EXPECT_EQ(e.where, ModelError::Where::Rule);
  EXPECT_EQ(e.index, 2u);
}

}  // namespace
