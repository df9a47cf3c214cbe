#include "fuzzypid/sim/mismatch.hpp"

#include <cmath>
#include <cstdio>

namespace fuzzypid::sim {

std::string tick_mismatch(double tuned_tick_s, double tick_s) {
  if (!(tuned_tick_s > 0.0)) return {};
  const double tuned = tuned_tick_s;
  if (std::fabs(tuned - tick_s) <= 1e-9 * tuned) return {};
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "it was tuned at a %g ms tick and runs at %g ms: its tuning does not carry over "
                "(re-tune at this tick)",
                tuned * 1e3, tick_s * 1e3);
  return buf;
}

std::string feedforward_mismatch(const controller::ControllerSpec& controller,
                                 const Condition& condition) {
  if (!controller.feedforward.gravity || condition.gravity) return {};
  return "it adds gravity feed-forward, but the plant of condition " + condition.name +
         " has no gravity (--dynamics coupled --gravity, or keys dynamics = \"coupled\", "
         "gravity = true)";
}

}  // namespace fuzzypid::sim
