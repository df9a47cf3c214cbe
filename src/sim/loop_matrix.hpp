// The state-space form of one joint's sampled loop (margins.hpp), shared by the margins and the
// common-Lyapunov certificate (lyapunov.hpp). Internal to fuzzypid::sim: Eigen types never reach
// a public header.
#pragma once

#include <complex>
#include <vector>

#include <Eigen/Dense>

#include "fuzzypid/pid/gains.hpp"
#include "fuzzypid/sim/margins.hpp"

namespace fuzzypid::sim::detail {

// The plant over one tick h with a delay fraction f of a tick:
//   x_{k+1} = Φ x_k + g1 u_{k−m} + g0 u_{k−m−1},
// x = (θ, θ̇) or, with a current loop (torque_bandwidth_hz > 0), (θ, θ̇, v) where v is the lagged
// command: v̇ = w (u − v), θ̈ = c v − a θ̇, w = 2π torque_bandwidth_hz. With an elastic gear
// (gear_resonance_hz > 0) x = (θ_m, θ̇_m, θ_l, θ̇_l[, v]), the measured motor side first. Without a
// gear, Φ and the g are affine in the plant gain c for a fixed damping a (the certificate's
// vertices rely on it; it takes rigid loops only).
struct DiscretePlant {
  Eigen::MatrixXd phi;
  Eigen::VectorXd g1, g0;
};

[[nodiscard]] DiscretePlant discretise(const JointLoop& loop, double plant_gain, double fraction);

// The closed loop's state matrix with `gains` (continuous SI form) in place of the loop's, plant
// gain c = `plant_gain`, and a total delay of m + f ticks (f in [0, 1)). State: the plant's, then
// I_{k−1}, d_{k−1}, θ_{k−1}, then the commands still on their way u_{k−1} .. u_{k−len} (len = m,
// or m + 1 with a fraction; with an observer at least d_o + 1), then the observer's ŷ_{k−1},
// ŵ_{k−1}. Entries are multi-affine in (c, Kp, Ki, Kd) for fixed damping, tick,
// filter and delay, except that Ki = 0 freezes the integral (its row is then zero).
[[nodiscard]] Eigen::MatrixXd closed_loop_matrix(const JointLoop& loop,
                                                 const pid::Gains<double>& gains, double plant_gain,
                                                 int m, double f);

// The gain-independent terms of L at one frequency: L = (Kp a + Ki b + Kd c) / (1 + Kd g), g the
// velocity observer's path from the controller's own output back to its D term (0 without one).
struct ResponseTerms {
  std::complex<double> a, b, c, g;
};

// The terms over margins()'s frequency grid for one plant (tick, plant gain, damping, filter,
// derivative source, delay, current loop): computed once, they serve every gain triple.
struct PlantGrid {
  std::vector<double> omega_rad_s;
  std::vector<ResponseTerms> terms;
};

[[nodiscard]] PlantGrid plant_grid(const JointLoop& loop, const MarginOptions& options);

// margins() of `loop` with its grid's terms taken from `grid` (of the same plant and options;
// null: computed), the same numbers.
[[nodiscard]] LoopMargins margins(const JointLoop& loop, const MarginOptions& options,
                                  const PlantGrid* grid);

}  // namespace fuzzypid::sim::detail
