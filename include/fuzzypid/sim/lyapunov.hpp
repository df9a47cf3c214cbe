// A certificate that one joint's linear loop stays stable while its PID gains change on every
// tick (docs/margins.md, "The certificate for moving gains").
//
// The gains may take any value in a box [Kp_lo, Kp_hi] × [Ki_lo, Ki_hi] × [Kd_lo, Kd_hi] on every
// tick, in any order; the plant gain c = g / J any value in [c_min, c_max] (also changing every
// tick). The closed loop's state matrix A(c, Kp, Ki, Kd) of margins.hpp (ZOH plant, integrator,
// filtered derivative, delay, current loop) is multi-affine in (c, Kp, Ki, Kd), so every A the box
// can produce lies in the convex hull of the matrices at its corners. A symmetric P ≻ 0 with
//   A_vᵀ P A_v − P ≺ 0  at every corner v
// then holds for the whole hull, and V(x) = xᵀ P x shrinks on every tick whatever the sequence of
// gains and inertias: the loop is stable for gains that move every tick (a common quadratic
// Lyapunov function). The LMIs are solved with SDPA (Debian libsdpa-dev), then checked
// independently: the reported contraction is max_v ‖A_v‖_P computed with Eigen from the P SDPA
// returned, and the certificate holds only when it is below 1.
//
// When the whole inertia range has no common P, the range is split geometrically into 4, then
// 16 intervals with one P each (inertia_intervals): the inertia then varies slowly, as it
// does along a path, and the gains still switch on every tick.
//
// Assumptions, as printed with every certificate: a linear, rigid joint (no saturation, friction
// other than viscous, backlash or gear elasticity; with saturation and an integrator the result is
// local), the plant gain, damping and current-loop bandwidth inside their ranges, the gains
// inside the box. The damping a = b / J and the current loop's bandwidth enter the discretisation
// through exponentials, not affinely: the LMIs are solved at the ends of their ranges and P is
// checked at six values of each (ends, geometric middle, quarters), every combination.
// A loop with an elastic gear (JointLoop::gear_resonance_hz > 0) is refused: its state matrix is
// not affine in c (certify.hpp certifies the rigid loop here and the gear at frozen gains).
// A box whose Ki reaches 0 from above cannot be certified: at Ki = 0 the PID freezes its integral,
// which then holds its value (an eigenvalue 1, no decay).
//
// Part of fuzzypid::sim (set-up code: allocates; never called in a tick). Not thread-safe to the
// extent SDPA is not: call it from one thread at a time.
#pragma once

#include <cstddef>
#include <limits>
#include <string>

#include "fuzzypid/pid/gains.hpp"
#include "fuzzypid/sim/margins.hpp"

namespace fuzzypid::sim {

// Gains in continuous SI form, low <= high componentwise.
struct GainBox {
  pid::Gains<double> low{};
  pid::Gains<double> high{};
};

struct SwitchingLoop {
  // Tick, derivative filter and source, delay and current loop; its gains, plant gain and
  // damping are replaced by the ranges below.
  JointLoop loop{};
  GainBox gains{};
  double plant_gain_min = 0.0, plant_gain_max = 0.0;        // c, rad/s² per unit of u, > 0
  double damping_min_per_s = 0.0, damping_max_per_s = 0.0;  // a = b / J, 1/s, >= 0
  // The current loop's bandwidth range, Hz: both 0 (an ideal current loop, the loop's own
  // torque_bandwidth_hz ignored) or both > 0.
  double torque_bandwidth_min_hz = 0.0, torque_bandwidth_max_hz = 0.0;
};

struct LyapunovCertificate {
  bool certified = false;
  // max over the corners (and the damping check points) of ‖A‖_P: V shrinks at least by its
  // square on every tick. NaN when no P was found.
  double contraction = std::numeric_limits<double>::quiet_NaN();
  // λmax(P) / λmin(P): a trajectory's norm stays below sqrt of it times its start's.
  double condition_number = std::numeric_limits<double>::quiet_NaN();
  // 1: one P for the whole inertia range, which may then change on every tick. k > 1: no such P;
  // the range split geometrically into k intervals has one P each: the inertia may change every
  // tick within an interval and slowly across them (every frozen inertia is covered).
  std::size_t inertia_intervals = 0;
  std::size_t states = 0;    // of the closed loop
  std::size_t vertices = 0;  // state matrices in the LMIs
  std::string reason;        // why not certified; empty when certified
  // When no P is found: the largest ρ(A_{s_n} ⋯ A_{s_1})^{1/n} over the periodic sequences of
  // corners s of period n <= 4 (a lower bound of the joint spectral radius). At or above 1 the
  // loop is truly destabilised by that switching, not just beyond what a quadratic V can prove;
  // below 1 the refusal may be conservative. NaN when not searched.
  double switching_radius = std::numeric_limits<double>::quiet_NaN();
  std::size_t switching_period = 0;  // n of the sequence that gives switching_radius
};

// The common quadratic Lyapunov function of `set` (see above). Invalid ranges (not finite,
// non-positive plant gain or tick, low > high) give certified = false with the reason.
[[nodiscard]] LyapunovCertificate common_lyapunov(const SwitchingLoop& set);

// The words every certificate carries (docs, controller files, exported headers).
[[nodiscard]] const char* lyapunov_assumptions() noexcept;

}  // namespace fuzzypid::sim
