// The controlled plant: the arm's joints driven by torques, integrated over one controller tick.
//
// Decoupled mode (default), per joint i:
//     J_i θ̈_i = sat(τ_i) − b_i θ̇_i + d_i
//     J_i = s_i · M_ii(q) + J_motor,i
// with M_ii the diagonal of the links' joint-space inertia (KDL ChainDynParam), s_i
// `inertia_scale`, J_motor,i the reflected motor inertia (`armature_kgm2`), b_i viscous damping,
// d_i a disturbance torque and sat() the clamp to ±torque limit. J is evaluated once per tick at
// the state at the start of the tick (InertiaUpdate::EveryTick) or once for good
// (InertiaUpdate::Fixed).
//
// Coupled mode: M_eff(q) q̈ = sat(τ) − C(q, q̇) q̇ − g(q) − b q̇ + d, with
// M_eff = S^½ M(q) S^½ + diag(J_motor), S = diag(s), M, C and g re-evaluated at every RK4 stage
// (fixed-size recursive Newton-Euler and composite-rigid-body algorithms over the model's chain,
// equal to KDL's ChainDynParam within 1e-12 relative), and gravity off by default (the paper's
// model has none). With InertiaUpdate::Fixed, M_eff is the one of the fixed configuration and only
// C q̇ + g vary.
//
// The torque and disturbance are held over the tick (zero-order hold), so the motion within a tick
// is smooth.
//
// What real joints have, each off by default (a default PlantConfig integrates bit for bit as
// without these fields):
//   - delay_s D: the command given to step() reaches the joint D seconds later (the time from
//     sampling the joint to the torque acting: one tick is a digital drive's usual computation
//     delay). Over a step the joint gets the newest command issued at least D before each instant,
//     zero torque before the first; a step is cut where a later command arrives, so D need not be
//     whole ticks (D mod dt: the previous command, then the new one). The plant keeps the last
//     kDelayCommands commands (a fixed ring: D may span at most kDelayCommands - 2 steps; beyond,
//     the oldest kept is held).
//   - torque_bandwidth_hz F: the current loop, a first-order lag on the (delayed, clamped)
//     command u: τ̇ = ω_c (u − τ), ω_c = 2π F, integrated exactly over each segment of constant u
//     (τ(t) = u + (τ₀ − u) e^(−ω_c t)), τ = 0 at reset. The torque limit clamps u (the current
//     reference), so τ stays within it. 0: an ideal loop, τ = u.
//   - coulomb_nm C_i, stribeck_nm S_i, stribeck_velocity_rad_s v_s: Coulomb friction with a
//     Stribeck peak (Armstrong-Hélouvry's exponential form with exponent 2), opposing the joint's
//     velocity beside the viscous b_i θ̇_i:
//         F_i(θ̇) = tanh(θ̇ / v_ε) (C_i + (max(S_i, C_i) − C_i) e^(−(θ̇ / v_s)²)),
//     the sign smoothed over v_ε = coulomb_smoothing_rad_s so that RK4 stays well-posed. A
//     torque below the peak leaves a joint at rest but for a creep where F_i(θ̇) equals it
//     (|θ̇| < v_ε atanh(τ / S_i), 0.55 v_ε at half the peak); above C_i it accelerates at
//     (τ − C_i) / J_i once |θ̇| >> v_ε, v_s. Coupled: F(q̇) joins the right-hand side.
//   - encoder_counts N: measured_position() is the angle quantised to 2π/N (the nearest count) and
//     measured_velocity() the difference of the last two readings over the step's dt, as a drive
//     computes them (the true velocity right after reset()). 0: the true angle and velocity.
//   - joint_resonance_hz F_i, joint_damping_ratio ζ: an elastic gear as a two-mass joint, the
//     motor side the armature J_m,i (which must be > 0), the link side the arm (J_l,i = s_i M_ii
//     decoupled; M(q) without the elastic joints' armature coupled), coupled by the gear torque
//     τ_g = k_i (θ_m − θ) + c_i (θ̇_m − θ̇):
//         J_m θ̈_m = τ − b θ̇_m − F(θ̇_m) − τ_g,    J_l θ̈ = τ_g + d   (coupled: M q̈ + C q̇ + g = τ_g + d)
//     with k_i = ω_i² μ_i, c_i = 2 ζ ω_i μ_i, ω_i = 2π F_i and μ_i = 1 / (1/J_m,i + 1/J_l,i) at
//     reset() (the free oscillation of the joint at F_i, damped by ζ). Friction acts on the motor
//     side. The drive measures the motor side (a motor encoder, as usual): measured_position()
//     and measured_velocity() are θ_m, θ̇_m (quantised by the encoder, if any); position() and
//     velocity() stay the link's, the angle the tool follows. reset() starts the motor where the
//     link is (the gear unloaded). F_i = 0: a rigid joint (armature on the link side).
//   - backlash_rad B: a dead zone of B (total play) in the gear of every elastic joint: the gear
//     torque is 0 while |θ_m − θ| <= B/2, else k (θ_m − θ ∓ B/2) + c (θ̇_m − θ̇). Needs
//     joint_resonance_hz (valid() is false otherwise). The contact is not smoothed: RK4's error
//     at each impact is of the step's first order.
// Every stiff term enters the step rule (step_rate_limit): viscous b_i, friction's steepest slope
// (max(S_i, C_i) / v_ε + (max(S_i, C_i) − C_i) √(2/e) / v_s; over J_m,i on an elastic joint),
// ω_c and the gear's 4 ω_i max(1, 2ζ) (h ω_i <= 0.0625: a 5 s run at 20 Hz stays within 2e-7 rad
// of a ten times finer step). With an elastic joint every tick is cut into equal substeps
// (no motion bound).
//
// The state is integrated with classical RK4: decoupled at `substep_s`, the last substep
// shortened to land exactly on the tick; coupled in equal substeps sized by `coupled_substep_s` and
// `coupled_step_rad`; in both modes no longer than the stiffness bound `step_rate_limit` allows
// (see PlantConfig). step() does not allocate, throw or print.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>

#include "fuzzypid/robot/robot_model.hpp"
#include "fuzzypid/robot/types.hpp"

namespace fuzzypid::robot {

enum class PlantCoupling : std::uint8_t { Decoupled, Coupled };
enum class InertiaUpdate : std::uint8_t { EveryTick, Fixed };

struct PlantConfig {
  PlantCoupling coupling = PlantCoupling::Decoupled;
  InertiaUpdate inertia_update = InertiaUpdate::EveryTick;
  // Configuration at which a Fixed inertia is evaluated; nullopt = the configuration of reset().
  std::optional<JointVector> fixed_configuration_rad;
  // Reflected motor inertia (rotor inertia × gear ratio²), kg·m². None by default: a URDF has no
  // armature field, and no robot's estimate fits another (the bundled ER50-C20's is
  // kEr50ArmatureKgm2, which sim::Experiment gives that robot).
  JointVector armature_kgm2 = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  // Multiplies the link inertia (payload scenarios); the armature is not scaled.
  JointVector inertia_scale = {1.0, 1.0, 1.0, 1.0, 1.0, 1.0};
  // Viscous damping b_i, N·m·s/rad. Zero: a pure double integrator.
  JointVector damping_nms = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  // |τ_i| is clamped to this; nullopt = the URDF effort limits.
  std::optional<JointVector> torque_limit_nm;
  bool gravity = false;        // coupled mode only
  double gravity_m_s2 = 9.81;  // along -z of the root frame
  double substep_s = 1e-3;     // RK4 step of the decoupled mode, s, > 0
  // RK4 step of the coupled mode: each tick is cut into equal substeps no longer than
  // coupled_substep_s (s, > 0) nor than the time in which any joint, at the tick's initial q̇ and
  // q̈, moves coupled_step_rad (rad, > 0; +inf disables the bound); at most 1000 substeps. RK4's
  // error grows with how far the state moves within a step, so slow motion takes whole ticks and
  // fast motion short steps. The defaults keep a 5 s run within 1e-6 rad of the same run with
  // both divided by 10 (docs/performance.md, "Coupled plant with gravity").
  double coupled_substep_s = 0.05;
  double coupled_step_rad = 0.015;
  // Stiffness bound of both modes: every substep h also satisfies h·λ <= step_rate_limit, with λ
  // the fastest rate of the terms that oppose velocity (viscous friction: λ = max b_i / J_i
  // decoupled; coupled, the largest eigenvalue of M_eff⁻¹ diag(b) at the tick's start).
  // Dimensionless, > 0. RK4 is stable for h·λ <= 2.785; 0.25 keeps a 5 s run at 100/s of viscous
  // friction within 4e-9 rad of the same run with every step ten times finer
  // (JointPlant.HighFrictionDefaultStepStaysWithinAMicroradianOfATenTimesFinerStep) and leaves
  // the coupled 50 ms step alone up to 5/s (the shipped conditions' friction: their results are
  // unchanged). In coupled mode this bound and coupled_substep_s hold even beyond 1000 substeps.
  double step_rate_limit = 0.25;
  // What real joints have (see the top of this file); 0 = off for each.
  double delay_s = 0.0;                   // command to torque, s, >= 0
  double torque_bandwidth_hz = 0.0;       // current loop bandwidth F, Hz, >= 0
  JointVector coulomb_nm{};               // Coulomb friction C_i, N·m, >= 0
  JointVector stribeck_nm{};              // Stribeck peak S_i, N·m, >= 0 (below C_i: no peak)
  double stribeck_velocity_rad_s = 0.01;  // v_s, rad/s, > 0
  double coulomb_smoothing_rad_s = 1e-3;  // v_ε, rad/s, > 0
  std::uint64_t encoder_counts = 0;       // counts per revolution N; 0: an ideal sensor
  JointVector joint_resonance_hz{};       // gear resonance F_i, Hz, >= 0 (0: rigid)
  double joint_damping_ratio = 0.0;       // ζ of the gear's resonance, >= 0
  double backlash_rad = 0.0;              // total play B of the elastic gears, rad, >= 0
};

// Commands the plant keeps for delay_s (see the top of this file).
inline constexpr std::size_t kDelayCommands = 64;

enum class PlantStatus : std::uint8_t {
  Ok,
  Saturated,       // stepped, but at least one torque was clamped (see saturated())
  InvalidInput,    // a non-finite torque or disturbance, or dt not finite and > 0: nothing changed
  NumericalError,  // the dynamics produced a non-finite state: nothing changed
};

[[nodiscard]] constexpr const char* to_string(PlantStatus s) noexcept {
  switch (s) {
    case PlantStatus::Ok:
      return "ok";
    case PlantStatus::Saturated:
      return "saturated";
    case PlantStatus::InvalidInput:
      return "invalid_input";
    case PlantStatus::NumericalError:
      return "numerical_error";
  }
  return "unknown";
}

// The gear of a two-mass joint (PlantConfig::joint_resonance_hz): the stiffness k = ω² μ
// (N·m/rad) and damping c = 2 ζ ω μ (N·m·s/rad) that give the joint its free resonance
// ω = 2π resonance_hz with damping ratio ζ, μ = 1 / (1/J_m + 1/J_l) from the motor and link
// inertias (kg·m², > 0). JointPlant fixes them so at reset(); the margins (sim/certify) use the same.
struct GearCoupling {
  double stiffness_nm_per_rad = 0.0;
  double damping_nms = 0.0;
};
[[nodiscard]] GearCoupling gear_coupling(double resonance_hz, double damping_ratio,
                                         double motor_kgm2, double link_kgm2) noexcept;

class JointPlant {
 public:
  // Copies the model. An invalid configuration (non-positive substep, negative armature, scale,
  // damping or torque limit, or a Fixed inertia that is not positive) is reported by valid().
  JointPlant(const RobotModel& model, const PlantConfig& config = {});
  JointPlant(const JointPlant& other);
  JointPlant(JointPlant&& other) noexcept;
  JointPlant& operator=(const JointPlant& other);
  JointPlant& operator=(JointPlant&& other) noexcept;
  ~JointPlant();

  // False if the configuration was rejected; step() then returns InvalidInput.
  bool valid() const noexcept;

  // Sets the state (rad, rad/s) and, with InertiaUpdate::Fixed and no fixed configuration, the
  // configuration at which the inertia is evaluated.
  void reset(const JointVector& q_rad, const JointVector& qd_rad_s) noexcept;

  // Advances by dt_s with torque_nm and disturbance_nm held constant.
  [[nodiscard]] PlantStatus step(const JointVector& torque_nm, double dt_s,
                                 const JointVector& disturbance_nm = {}) noexcept;

  const JointVector& position() const noexcept;  // rad
  const JointVector& velocity() const noexcept;  // rad/s
  // What the drive measures (encoder_counts; position() and velocity() without an encoder).
  const JointVector& measured_position() const noexcept;  // rad
  const JointVector& measured_velocity() const noexcept;  // rad/s
  // The motor side's angle of the two-mass joint (position() for rigid joints), rad.
  const JointVector& motor_position() const noexcept;
  // rad/s², at the end of the last tick (0 after reset()). In coupled mode it is evaluated on the
  // first call after a tick (no allocation), NaN if M_eff is not positive definite there; with an
  // elastic joint it is the link's, evaluated at the end of every tick.
  const JointVector& acceleration() const noexcept;
  const JointVector& inertia() const noexcept;  // effective J_i of the last tick, kg·m²
  // The torque reaching the joint at the end of the last tick: the clamped command, delayed and
  // lagged when delay_s, torque_bandwidth_hz say so.
  const JointVector& applied_torque() const noexcept;
  const std::array<bool, kNumJoints>& saturated() const noexcept;
  double time_s() const noexcept;  // sum of accepted dt since reset()

  const PlantConfig& config() const noexcept;
  const RobotModel& model() const noexcept;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fuzzypid::robot
