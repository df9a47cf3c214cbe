// Stability margins of one joint's linear loop at frozen gains (docs/margins.md).
//
// The loop, sampled at the controller tick h:
//   plant       J θ̈ = τ − b θ̇ with τ = g u held over the tick (zero-order hold); g = J^ with
//               acceleration gain units (sim::Experiment::torque_from_command), 1 with torque
//               units. In the loop only c = g / J (rad/s² per unit of u) and a = b / J (1/s) count.
//   controller  the library's PID as pid::Pid runs it on a regulation problem (setpoint 0,
//               e = −θ): P = Kp e, I_k = I_{k−1} + Ki e_k h, d_raw = −θ̇_k (DerivativeSource::Rates)
//               or (e_k − e_{k−1}) / h (Difference), d_k = d_{k−1} + β (d_raw − d_{k−1}) with
//               β = h / (Tf + h), u_k = P + I_k + Kd d_k; gains in continuous SI form.
//               DerivativeOn does not matter here: with a constant setpoint both give the same d.
//               With DerivativeSource::Observer d_raw = −ŵ_k, the velocity observer's estimate
//               (x̂ = (ŷ, ŵ): x̂_k = Φo x̂_{k−1} + Γo c_m u_{k−1−d_o} + K θ_k, Φo = (I − K C) A,
//               Γo = (I − K C) B for the double integrator A, B at h, C = (1 0), K = (l1, l2 / h)).
//   current loop (torque_bandwidth_hz F > 0) the plant receives v, the command lagged to first
//               order: v̇ = 2π F (u_delayed − v), as robot::Plant applies torque_bandwidth_hz;
//               discretised exactly (matrix exponential) with the ZOH.
//   gear        (gear_resonance_hz F > 0) an elastic gear, as robot::Plant's joint_resonance_hz: a
//               two-mass joint whose motor side carries the fraction r of J (the armature) and the
//               viscous friction, is driven by the command and is what the drive measures (θ, θ̇
//               above are the motor's θ_m, θ̇_m); the link side (1 − r) J follows through the gear
//               (δ = θ_m − θ_l, ω = 2π F, ζ = gear_damping_ratio):
//                   r θ̈_m = c v − a θ̇_m − g,   (1 − r) θ̈_l = g,   g = r (1 − r) (ω² δ + 2 ζ ω δ̇)
//               (g the gear torque over J; its stiffness ω² μ and damping 2 ζ ω μ with
//               μ = r (1 − r) J: F is the joint's free resonance at this inertia); v = u without a
//               current loop. Discretised exactly (matrix exponential) with the ZOH.
//   delay       u_k reaches the plant (d + f) h later (d = delay_ticks, f = delay_fraction in
//               [0, 1)): over each tick the plant sees u_{k−d−1} for f h, then u_{k−d} (the
//               modified z-transform of the ZOH plant; exact, not a Padé or e^{−jωτ} model).
// Broken at the plant input, the loop transfer is (1 + L = 0 closes it)
//   L(z) = z^−d [ (Kp + Ki h z / (z − 1)) Pθ(z) + Kd F(z) D(z) ],
//   F(z) = β z / (z − 1 + β),  D = Pω (Rates) or (1 − z^−1) Pθ / h (Difference),
// with Pθ, Pω the ZOH transfers from u to θ and θ̇ (the fraction f of a tick included). With the
// observer, ŵ = Gθ(z) θ + Gu(z) u, so D = Gθ Pθ and the loop is
//   L(z) = z^−d [ (Kp + Ki h z / (z − 1)) Pθ(z) + Kd F(z) Gθ(z) Pθ(z) ] / (1 + Kd F(z) Gu(z)),
// Gθ = e2ᵀ (I − Φo/z)⁻¹ K, Gu = e2ᵀ (I − Φo/z)⁻¹ Γo c_m z^−(1+d_o). Its gain margin is that of
// the plant's gain (L scales with c; closed_loop_spectral_radius scales c, not the PID's gains,
// which with an observer is not the same).
//
// The margins follow MATLAB's allmargin and diskmargin:
//   gain margin     at each phase crossover ω_p (L(e^{jω_p h}) real and negative, including the
//                   Nyquist frequency π/h), the factor 1/|L|; gain_margin_db is the smallest above
//                   1 (+inf: none), gain_margin_low_db the largest below 1 (−inf: none);
//   phase margin    at each gain crossover ω_c (|L| = 1), 180° + ∠L wrapped to (−180°, 180°];
//                   the smallest is reported;
//   delay margin    at each gain crossover, the phase margin wrapped to [0°, 360°) over ω_c: the
//                   extra transport delay (s) that brings L through −1; the smallest is reported.
//                   delay_margin_ticks is the discrete count: the fewest extra whole ticks of
//                   delay after which the closed loop's state matrix has a pole on or outside the
//                   unit circle (checked on the eigenvalues); delay_margin_exact_s the same for
//                   any extra delay, whole ticks or not (bisection on the eigenvalues of the
//                   sampled-data loop with a fractional delay): the "discrete" delay margin;
//   disk margin     balanced (skew σ = 0): α = 1 / max_ω |S − 1/2| with S = 1 / (1 + L), over a
//                   dense logarithmic grid up to π/h refined around its peak; 0 when the nominal
//                   loop is unstable. The loop tolerates every simultaneous gain and phase change
//                   in the disk: gain factors in [(1 − α/2)/(1 + α/2), (1 + α/2)/(1 − α/2)]
//                   (+inf above α = 2) and phase changes within ±2 atan(α/2).
// All margins are those of a loop whose gains are frozen; they say nothing about gains that move
// every tick (Shamma and Athans, 1991).
//
// Part of fuzzypid::sim (set-up code: it allocates; never called in a tick).
#pragma once

#include <cmath>
#include <complex>

#include "fuzzypid/pid/gains.hpp"
#include "fuzzypid/pid/pid.hpp"

namespace fuzzypid::sim {

struct JointLoop {
  double tick_s = 0.05;              // h, > 0
  double plant_gain = 1.0;           // c = g / J, rad/s² per unit of u, > 0
  double damping_per_s = 0.0;        // a = b / J, 1/s, >= 0
  pid::Gains<double> gains{};        // Kp, Ki (1/s), Kd (s): continuous SI form
  double derivative_filter_s = 0.0;  // Tf, s
  pid::DerivativeSource derivative = pid::DerivativeSource::Rates;
  int delay_ticks = 0;          // d >= 0
  double delay_fraction = 0.0;  // f in [0, 1): the part of a tick beyond d
  // The current loop, a first-order lag on the (delayed) command, Hz; 0: ideal (robot::PlantConfig's
  // torque_bandwidth_hz). With it the plant is θ̈ = c v − a θ̇, v̇ = 2π F (u − v).
  double torque_bandwidth_hz = 0.0;
  // The elastic gear: its free resonance at this inertia (Hz; 0: a rigid joint), its damping ratio
  // (>= 0) and the motor side's share of the joint's inertia r = J_m / J (in (0, 1) with a gear).
  double gear_resonance_hz = 0.0;
  double gear_damping_ratio = 0.0;
  double motor_inertia_fraction = 1.0;
  // DerivativeSource::Observer (pid.hpp): the observer's bandwidth F (Hz, > 0), the ticks of delay
  // it models (0 .. pid::kMaxObserverDelayTicks) and its model's c (rad/s² per unit of u: 1 with
  // acceleration gain units, whatever the plant's c is).
  double observer_bandwidth_hz = 0.0;
  int observer_delay_ticks = 1;
  double observer_plant_gain = 1.0;
};

struct LoopMargins {
  bool stable = false;                               // the nominal closed loop: spectral radius < 1
  double spectral_radius = 0.0;                      // of the closed-loop state matrix
  double gain_margin_db = 0.0;                       // upper (+inf: none)
  double gain_margin_low_db = 0.0;                   // lower (−inf: none)
  double phase_crossover_rad_s = 0.0;                // of gain_margin_db (NaN: none)
  double phase_margin_deg = 0.0;                     // +inf: no gain crossover
  double gain_crossover_rad_s = 0.0;                 // of phase_margin_deg (NaN: none)
  double delay_margin_s = 0.0;                       // +inf: no gain crossover
  int delay_margin_ticks = -1;                       // -1: not computed or not found
  double delay_margin_exact_s = NAN;                 // s; NaN: not computed or not found
  double disk_margin = 0.0;                          // α
  double disk_gain_low = 0.0, disk_gain_high = 0.0;  // factors (high +inf for α >= 2)
  double disk_phase_deg = 0.0;                       // ±
  double disk_frequency_rad_s = 0.0;                 // where |S − 1/2| peaks
};

// L(e^{jωh}) of the loop (ω in rad/s, 0 < ω <= π/h).
[[nodiscard]] std::complex<double> loop_response(const JointLoop& loop, double omega_rad_s);

// Spectral radius of the closed loop with the loop gain scaled by `gain_scale` (all three PID
// gains multiplied; with an observer, the plant's gain) and `extra_delay_ticks` more ticks of delay.
[[nodiscard]] double closed_loop_spectral_radius(const JointLoop& loop, double gain_scale = 1.0,
                                                 int extra_delay_ticks = 0);

// The same for `extra_delay_s` more delay (s, any value >= 0: whole ticks and a fraction).
[[nodiscard]] double closed_loop_spectral_radius_at_delay(const JointLoop& loop,
                                                          double extra_delay_s);

// Sets the loop's delay_ticks and delay_fraction to `delay_s` (>= 0) at its tick.
void set_delay(JointLoop& loop, double delay_s);

struct MarginOptions {
  int grid_points = 2000;  // logarithmic grid from 1e-5 π/h to π/h
  // Compute delay_margin_ticks and delay_margin_exact_s (eigenvalues of growing loops).
  bool delay_ticks = true;
};

// The margins above. A loop with invalid numbers (non-positive tick or plant gain, negative
// damping, filter or delay, non-finite gains; with a gear a motor share outside (0, 1) or a
// negative damping ratio) gives stable = false and zero margins.
[[nodiscard]] LoopMargins margins(const JointLoop& loop, const MarginOptions& options = {});

// The gain factor of a margin in dB (20 log10).
[[nodiscard]] double to_db(double factor) noexcept;

}  // namespace fuzzypid::sim
