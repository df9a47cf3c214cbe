// What a controller file says about the plant it was made for, against the condition it is run
// on: set-up checks the tools print as warnings (the run goes ahead; the result may not mean what
// the controller's record suggests).
#pragma once

#include <string>

#include "fuzzypid/controller/controller_spec.hpp"
#include "fuzzypid/sim/condition.hpp"

namespace fuzzypid::sim {

// Empty, or why running a controller tuned at a `tuned_tick_s` controller tick (the tick_s its
// controller file records in [tuning]) at a `tick_s` tick departs from its tuning: its gains, its ringing and its
// margins there say nothing about this tick (a controller tuned at 4 ms can diverge at 50 ms). A
// relative difference below 1e-9 counts as the same tick; no recorded tick (0) passes.
[[nodiscard]] std::string tick_mismatch(double tuned_tick_s, double tick_s);

// Empty, or why `controller`'s gravity feed-forward does not fit `condition`: it adds g^(q_d)
// to the torque of a plant without gravity, so that torque pushes the arm off its path instead
// of holding it up.
[[nodiscard]] std::string feedforward_mismatch(const controller::ControllerSpec& controller,
                                               const Condition& condition);

}  // namespace fuzzypid::sim
