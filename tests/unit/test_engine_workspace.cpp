// The engine's workspaces as a specification: what a view must hold for a model (fits), the
// previous outputs starting unknown (NaN), and DynamicWorkspace sized to its model.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "engine_test_models.hpp"
#include "fuzzypid/fuzzy/engine_workspace.hpp"

namespace {

using fuzzypid::fuzzy::DynamicWorkspace;
using fuzzypid::fuzzy::EngineWorkspace;
using fuzzypid::fuzzy::Token;
using fuzzypid::test::conclusion;
using fuzzypid::test::proposition;
using fuzzypid::test::ramp_model;

TEST(EngineWorkspace, PreviousOutputsStartUnknown) {
  auto ws = std::make_unique<EngineWorkspace<double>>();
  for (const double v : ws->previous)
    EXPECT_TRUE(std::isnan(v));
  const auto model = ramp_model();
  EXPECT_TRUE(ws->view().fits(*model));
}

TEST(DynamicWorkspace, IsSizedToItsModel) {
  const auto model = ramp_model(true);
  DynamicWorkspace<double> ws(*model);
  EXPECT_EQ(ws.stride, 2u);
  EXPECT_EQ(ws.strength.size(), 2u);
  EXPECT_EQ(ws.previous.size(), 2u);
  EXPECT_TRUE(std::isnan(ws.previous[0]));
  EXPECT_TRUE(ws.degree.empty());  // no antecedent tests an output
  EXPECT_TRUE(ws.view().fits(*model));
}

TEST(DynamicWorkspace, AChainedModelNeedsTheOutputsTermDegrees) {
  auto model = ramp_model(true);
  const Token on_output = proposition(0, 1, Token::Kind::OutputProposition);
  const auto c = conclusion(1, 0);
  ASSERT_TRUE(model->add_rule(&on_output, 1, &c, 1));
  DynamicWorkspace<double> ws(*model);
  EXPECT_EQ(ws.degree.size(), 2u * ws.stride);
  EXPECT_TRUE(ws.view().fits(*model));
  auto without_degrees = ws.view();
  without_degrees.degree = nullptr;
  EXPECT_FALSE(without_degrees.fits(*model));
}

}  // namespace
