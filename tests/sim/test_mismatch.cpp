// What a controller file was made for against what it runs on (fuzzypid/sim/mismatch.hpp): the
// training tick and gravity feed-forward on a plant without gravity.
#include <gtest/gtest.h>

#include <string>

#include "fuzzypid/sim/mismatch.hpp"

namespace {

namespace controller = fuzzypid::controller;
namespace sim = fuzzypid::sim;

TEST(TickMismatch, AControllerRunAtAnotherTickThanItsTrainingOneIsNamedWithBothTicks) {
  const std::string why = sim::tick_mismatch(0.004, 0.05);
  EXPECT_NE(why.find("tuned at a 4 ms tick and runs at 50 ms"), std::string::npos) << why;
  EXPECT_NE(sim::tick_mismatch(0.05, 0.01), "");
}

TEST(TickMismatch, TheSameTickAndAnUnrecordedTickPass) {
  EXPECT_EQ(sim::tick_mismatch(0.01, 10.0 * 1e-3), "");  // the tick of tick_ms = 10
  EXPECT_EQ(sim::tick_mismatch(0.0, 0.05), "");
}

TEST(FeedforwardMismatch, GravityFeedForwardOnAPlantWithoutGravityIsNamedWithTheCondition) {
  controller::ControllerSpec s = controller::paper_pid();
  sim::Condition c;
  c.name = "flat";
  EXPECT_EQ(sim::feedforward_mismatch(s, c), "");  // no feed-forward
  s.feedforward.gravity = true;
  const std::string why = sim::feedforward_mismatch(s, c);
  EXPECT_NE(why.find("condition flat has no gravity"), std::string::npos) << why;
  c.dynamics = fuzzypid::robot::PlantCoupling::Coupled;
  c.gravity = true;
  EXPECT_EQ(sim::feedforward_mismatch(s, c), "");
}

}  // namespace
