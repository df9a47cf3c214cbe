// JointPlant: the equations are documented in plant.hpp.
#include "fuzzypid/robot/plant.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "rigid_body_dynamics.hpp"

namespace fuzzypid::robot {
namespace {

constexpr double kMaxCoupledSubsteps = 1000.0;
constexpr double kTwoPi = 6.283185307179586476925;
// The gear's rate in the step rule is this many times its ω max(1, 2ζ): an oscillation's phase
// error adds up over its periods, so it needs h ω <= step_rate_limit / 4 (0.0625) to keep a 5 s
// run at 20 Hz within 1e-6 rad of a ten times finer step (1.7e-7 coupled, 6e-8 decoupled;
// JointPlant.ResonantGearDefaultStepStaysWithinAMicroradianOfATenTimesFinerStep).
constexpr double kGearRateFactor = 4.0;

// A torque command and when it was issued (plant time, s): the delay line's entries.
struct DelayedCommand {
  double issued_s = 0.0;
  JointVector torque_nm{};
};

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

Vec6 to_vec(const JointVector& v) noexcept {
  return Eigen::Map<const Vec6>(v.data());
}

JointVector to_array(const Vec6& v) noexcept {
  JointVector a{};
  Eigen::Map<Vec6>(a.data()) = v;
  return a;
}

bool all_finite(const JointVector& v) noexcept {
  for (double x : v) {
    if (!std::isfinite(x)) return false;
  }
  return true;
}

bool all_non_negative(const JointVector& v) noexcept {
  for (double x : v) {
    if (!(x >= 0.0)) return false;
  }
  return true;
}

// The plant's RobotData, made for its own copy of the model. A copied slot starts empty: the copy
// of a plant makes its own for its own model (JointPlant's copy constructor and assignment).
struct DataSlot {
  std::optional<RobotData> data;
  DataSlot() = default;
  DataSlot(const DataSlot& /*other*/) noexcept {}
  DataSlot& operator=(const DataSlot& /*other*/) noexcept {
    data.reset();
    return *this;
  }
  DataSlot(DataSlot&&) noexcept = default;
  DataSlot& operator=(DataSlot&&) noexcept = default;
  ~DataSlot() = default;
};

}  // namespace

GearCoupling gear_coupling(double resonance_hz, double damping_ratio, double motor_kgm2,
                           double link_kgm2) noexcept {
  const double omega = kTwoPi * resonance_hz;
  const double reduced = 1.0 / (1.0 / motor_kgm2 + 1.0 / link_kgm2);
  return {omega * omega * reduced, 2.0 * damping_ratio * omega * reduced};
}

class JointPlant::Impl {
 public:
  Impl(const RobotModel& m, const PlantConfig& c) : model(m), config(c) {
    slot.data.emplace(model);
    limit = config.torque_limit_nm.value_or(model.effort_limits_nm());
    valid = std::isfinite(config.substep_s) && config.substep_s > 0.0 &&
            std::isfinite(config.coupled_substep_s) && config.coupled_substep_s > 0.0 &&
            config.coupled_step_rad > 0.0 && all_non_negative(config.armature_kgm2) &&
            all_finite(config.armature_kgm2) && all_non_negative(config.inertia_scale) &&
            all_finite(config.inertia_scale) && all_non_negative(config.damping_nms) &&
            all_finite(config.damping_nms) && all_non_negative(limit) &&
            std::isfinite(config.gravity_m_s2) &&
            (!config.fixed_configuration_rad || all_finite(*config.fixed_configuration_rad));
    valid = valid && std::isfinite(config.step_rate_limit) && config.step_rate_limit > 0.0 &&
            std::isfinite(config.delay_s) && config.delay_s >= 0.0 &&
            std::isfinite(config.torque_bandwidth_hz) && config.torque_bandwidth_hz >= 0.0 &&
            all_finite(config.coulomb_nm) && all_non_negative(config.coulomb_nm) &&
            all_finite(config.stribeck_nm) && all_non_negative(config.stribeck_nm) &&
            std::isfinite(config.stribeck_velocity_rad_s) && config.stribeck_velocity_rad_s > 0.0 &&
            std::isfinite(config.coulomb_smoothing_rad_s) && config.coulomb_smoothing_rad_s > 0.0;
    sqrt_scale = to_vec(config.inertia_scale).cwiseSqrt();
    lag_rate = kTwoPi * config.torque_bandwidth_hz;
    // The slopes of the torques that oppose velocity, N·m·s/rad: what makes the plant stiff.
    // Friction's steepest slope: (peak) / smoothing at rest, plus the Stribeck fall's
    // (peak − C) √(2/e) / v_s.
    stiffness = config.damping_nms;
    for (std::size_t i = 0; i < kNumJoints; ++i) {
      const double c = config.coulomb_nm[i];
      const double peak = std::fmax(config.stribeck_nm[i], c);
      coulomb = coulomb || peak > 0.0;
      if (peak > 0.0)
        stiffness[i] += peak / config.coulomb_smoothing_rad_s + (peak - c) *
                                                                    std::sqrt(2.0 / std::exp(1.0)) /
                                                                    config.stribeck_velocity_rad_s;
      stiff = stiff || stiffness[i] > 0.0;
    }
    if (config.encoder_counts > 0)
      encoder_step = kTwoPi / static_cast<double>(config.encoder_counts);
    valid = valid && all_finite(config.joint_resonance_hz) &&
            all_non_negative(config.joint_resonance_hz) &&
            std::isfinite(config.joint_damping_ratio) && config.joint_damping_ratio >= 0.0 &&
            std::isfinite(config.backlash_rad) && config.backlash_rad >= 0.0;
    half_play = 0.5 * config.backlash_rad;
    for (std::size_t i = 0; i < kNumJoints; ++i) {
      if (!(config.joint_resonance_hz[i] > 0.0)) continue;
      elastic = true;
      elastic_mask[static_cast<int>(i)] = 1.0;
      // The motor side is the armature: an elastic joint needs one.
      valid = valid && config.armature_kgm2[i] > 0.0;
    }
    // Backlash lives in the gear of the two-mass joint.
    valid = valid && (config.backlash_rad == 0.0 || elastic);
    reset(JointVector{}, JointVector{});
  }

  void reset(const JointVector& q0, const JointVector& qd0) noexcept {
    q = q0;
    qd = qd0;
    qdd = JointVector{};
    qdd_pending = false;
    applied = JointVector{};
    saturated = {};
    time = 0.0;
    lag_torque = JointVector{};
    delay_count = 0;
    delay_head = 0;
    measured_q = quantised(q0);
    measured_qd = qd0;
    // Decoupled J_i = s_i M_ii + armature_i is the diagonal of the effective mass matrix.
    fixed_mass = effective_mass(config.fixed_configuration_rad.value_or(q0));
    inertia = to_array(config.inertia_update == InertiaUpdate::Fixed
                           ? Vec6(fixed_mass.diagonal())
                           : Vec6(effective_mass(q0).diagonal()));
    // The two-mass joint: the motor side starts where the link is (the gear unloaded); the gear's
    // stiffness and damping follow from the resonance and the two inertias at this configuration.
    xm = to_vec(q0);
    vm = to_vec(qd0);
    xm_out = q0;
    vm_out = qd0;
    gear_k = Vec6::Zero();
    gear_c = Vec6::Zero();
    if (elastic) {
      const Vec6 link = fixed_mass.diagonal() - to_vec(config.armature_kgm2);
      for (int i = 0; i < static_cast<int>(kNumJoints); ++i) {
        const auto k = static_cast<std::size_t>(i);
        if (elastic_mask[i] == 0.0) continue;
        const GearCoupling g =
            gear_coupling(config.joint_resonance_hz[k], config.joint_damping_ratio,
                          config.armature_kgm2[k], link[i]);
        gear_k[i] = g.stiffness_nm_per_rad;
        gear_c[i] = g.damping_nms;
      }
    }
  }

  // M_eff = S^½ M(x) S^½ + diag(armature) (the fixed configuration's with InertiaUpdate::Fixed)
  // and the bias C(x, v) v + g(x) of the coupled model.
  void effective_mass_and_bias(const Vec6& x, const Vec6& v, Mat6& m, Vec6& bias) const noexcept {
    const detail::RigidBodyDynamics& dynamics = detail::dynamics_of(model);
    const double g = config.gravity ? config.gravity_m_s2 : 0.0;
    if (config.inertia_update == InertiaUpdate::Fixed) {
      m = fixed_mass;
      bias = dynamics.bias(x, v, g);
      return;
    }
    dynamics.mass_and_bias(x, v, g, m, bias);
    m = sqrt_scale.asDiagonal() * m * sqrt_scale.asDiagonal();
    m.diagonal() += to_vec(config.armature_kgm2);
  }

  // The link-side acceleration of the two-mass joint (coupled or decoupled) for the link force
  // `f` (gear torque and disturbance on elastic joints; the drive, friction and disturbance on
  // rigid ones, whose armature stays on the link side). `j_link` is the decoupled link inertia.
  bool link_acceleration(const Vec6& x, const Vec6& v, const Vec6& f, const Vec6& j_link,
                         Vec6& a) const noexcept {
    if (config.coupling == PlantCoupling::Decoupled) {
      a = f.cwiseQuotient(j_link);
      return true;
    }
    Mat6 m;
    Vec6 bias;
    effective_mass_and_bias(x, v, m, bias);
    m.diagonal() -= to_vec(config.armature_kgm2).cwiseProduct(elastic_mask);
    const Eigen::LLT<Mat6> llt(m);
    if (llt.info() != Eigen::Success) return false;
    a = llt.solve(f - bias);
    return true;
  }

  // The encoder's reading of `angle`: the nearest multiple of encoder_step (the angle itself
  // without an encoder).
  JointVector quantised(const JointVector& angle) const noexcept {
    if (encoder_step == 0.0) return angle;
    JointVector out{};
    for (std::size_t i = 0; i < kNumJoints; ++i)
      out[i] = std::nearbyint(angle[i] / encoder_step) * encoder_step;
    return out;
  }

  // The longest step with h·rate <= step_rate_limit (+inf for rate 0).
  double stable_step(double rate) const noexcept {
    return rate > 0.0 ? config.step_rate_limit / rate : std::numeric_limits<double>::infinity();
  }

  // The fastest rate of the coupled model's linear terms, 1/s: the largest eigenvalue of
  // M_eff⁻¹ diag(stiffness), that of the symmetric L⁻¹ diag(stiffness) L⁻ᵀ (M_eff = L Lᵀ). 0 without
  // such terms.
  double coupled_rate(const Mat6& mass) const noexcept {
    if (!stiff) return 0.0;
    const Eigen::LLT<Mat6> llt(mass);
    if (llt.info() != Eigen::Success) return 0.0;
    const Mat6 w = llt.matrixL().solve(Mat6(to_vec(stiffness).cwiseSqrt().asDiagonal()));
    const Eigen::SelfAdjointEigenSolver<Mat6> eigen(w * w.transpose(), Eigen::EigenvaluesOnly);
    return eigen.info() == Eigen::Success ? eigen.eigenvalues().maxCoeff() : 0.0;
  }

  // S^½ M(q) S^½ + diag(armature).
  Mat6 effective_mass(const JointVector& at) noexcept {
    Mat6 m = sqrt_scale.asDiagonal() * model.mass_matrix(at, *slot.data) * sqrt_scale.asDiagonal();
    m.diagonal() += to_vec(config.armature_kgm2);
    return m;
  }

  // q̈ for the coupled model at (x, v), from the fixed-size RNEA/CRBA over the model's chain;
  // false if M_eff is not positive definite. `diagonal`, when given, receives diag(M_eff).
  bool coupled_acceleration(const Vec6& x, const Vec6& v, const Vec6& drive, Vec6& a,
                            Vec6* diagonal = nullptr, Mat6* mass = nullptr) const noexcept {
    Mat6 m;
    Vec6 bias;
    effective_mass_and_bias(x, v, m, bias);
    if (diagonal != nullptr) *diagonal = m.diagonal();
    if (mass != nullptr) *mass = m;
    Vec6 rhs = drive - to_vec(config.damping_nms).cwiseProduct(v) - bias;
    if (coulomb) rhs -= friction(v);
    const Eigen::LLT<Mat6> llt(m);
    if (llt.info() != Eigen::Success) return false;
    a = llt.solve(rhs);
    return true;
  }

  // The torque (N·m, at the joint, after the drive's limit) that opposes velocity beyond viscous
  // friction: Coulomb friction with a Stribeck peak, its sign smoothed over coulomb_smoothing_rad_s.
  Vec6 friction(const Vec6& v) const noexcept {
    Vec6 f;
    for (int i = 0; i < static_cast<int>(kNumJoints); ++i) {
      const auto k = static_cast<std::size_t>(i);
      const double c = config.coulomb_nm[k];
      const double peak = config.stribeck_nm[k] > c ? config.stribeck_nm[k] : c;
      const double r = v[i] / config.stribeck_velocity_rad_s;
      f[i] = std::tanh(v[i] / config.coulomb_smoothing_rad_s) * (c + (peak - c) * std::exp(-r * r));
    }
    return f;
  }

  // The k-th newest command of the delay line (k < delay_count).
  const DelayedCommand& delayed(std::size_t k) const noexcept {
    return delay_line[(delay_head + kDelayCommands - k) % kDelayCommands];
  }

  PlantStatus step(const JointVector& torque, double dt, const JointVector& disturbance) noexcept {
    if (!valid || !std::isfinite(dt) || !(dt > 0.0) || !all_finite(torque) ||
        !all_finite(disturbance)) {
      return PlantStatus::InvalidInput;
    }
    JointVector clamped{};
    std::array<bool, kNumJoints> sat{};
    bool any = false;
    for (std::size_t i = 0; i < kNumJoints; ++i) {
      clamped[i] = std::fmin(std::fmax(torque[i], -limit[i]), limit[i]);
      sat[i] = clamped[i] != torque[i];
      any = any || sat[i];
    }
    const Vec6 damping = to_vec(config.damping_nms);
    const Vec6 dist = to_vec(disturbance);
    const double wc = lag_rate;
    const bool delayed_drive = config.delay_s > 0.0;

    // The commands reaching the joint within this step: without delay, this one for the whole
    // step; with it, the newest command issued at least delay_s before each instant (zero torque
    // before the first one), so the step is cut where a later command arrives. Offsets within
    // 1e-9 dt of the step's ends count as the ends (a delay of whole ticks switches exactly there).
    // `next_command` is the index (newest = 0) of the command that arrives next, -1 when none does.
    long next_command = -1;
    JointVector command = clamped;
    double next_switch = dt;
    const double eps = 1e-9 * dt;
    if (delayed_drive) {
      delay_head = (delay_head + 1) % kDelayCommands;
      delay_line[delay_head] = {time, clamped};
      delay_count = std::min(delay_count + 1, kDelayCommands);
      std::size_t active = delay_count;
      for (std::size_t k = 0; k < delay_count; ++k) {
        if (delayed(k).issued_s + config.delay_s - time <= eps) {
          active = k;
          break;
        }
      }
      if (active == delay_count && delay_count == kDelayCommands) active = delay_count - 1;
      command = active < delay_count ? delayed(active).torque_nm : JointVector{};
      next_command = static_cast<long>(active) - 1;
    }
    // The offset of command k's arrival within this step (dt when it arrives later).
    const auto arrival = [&](long k) {
      if (k < 0) return dt;
      const double at = delayed(static_cast<std::size_t>(k)).issued_s + config.delay_s - time;
      return at >= dt - eps ? dt : std::fmax(at, 0.0);
    };
    if (delayed_drive) next_switch = arrival(next_command);

    Vec6 x = to_vec(q);
    Vec6 v = to_vec(qd);
    Vec6 a_end = Vec6::Zero();
    JointVector j_tick{};
    Vec6 lag = to_vec(lag_torque);  // the current loop's torque at the segment's start
    Vec6 mx = xm;                   // the motor side of a two-mass joint
    Vec6 mv = vm;
    Vec6 drive_end = to_vec(clamped) + dist;
    // Segments of one command each, [t0, t1) within the step.
    double t0 = 0.0;
    bool first = true;
    Vec6 inv_j = Vec6::Zero();
    double h_nominal = 0.0;
    while (true) {
      const double t1 = next_switch;
      const double length = t1 - t0;
      const Vec6 u = to_vec(command);
      // The drive at offset s into the segment: the command (after the current loop's first-order
      // lag, exact: τ(s) = u + (τ(0) − u) e^(−ω_c s)) plus the disturbance.
      const Vec6 held_drive = u + dist;
      const auto drive_at = [&](double s_in) -> Vec6 {
        if (wc == 0.0) return Vec6(held_drive);
        return u + (lag - u) * std::exp(-wc * s_in) + dist;
      };
      if (length > 0.0 && elastic) {
        // The two-mass joint: link (x, v) and motor (xm, vm) per joint, the gear between them;
        // rigid joints keep xm = x. Equal substeps within the configured step, the stiffness bound
        // (gear: ω_i max(1, 2ζ); friction and viscous on the motor side: slope / J_motor) and,
        // coupled, 1000 at most.
        Vec6 j_link = Vec6::Ones();
        if (first) {
          const Vec6 diag = config.inertia_update == InertiaUpdate::Fixed
                                ? Vec6(fixed_mass.diagonal())
                                : Vec6(effective_mass(q).diagonal());
          j_tick = to_array(diag);
        }
        j_link = to_vec(j_tick) - to_vec(config.armature_kgm2).cwiseProduct(elastic_mask);
        double rate = wc;
        for (int i = 0; i < static_cast<int>(kNumJoints); ++i) {
          const auto k = static_cast<std::size_t>(i);
          if (!(j_link[i] > 0.0) || !std::isfinite(j_link[i])) return PlantStatus::NumericalError;
          if (elastic_mask[i] != 0.0) {
            const double omega = kTwoPi * config.joint_resonance_hz[k];
            rate = std::fmax(
                rate, kGearRateFactor * omega * std::fmax(1.0, 2.0 * config.joint_damping_ratio));
            rate = std::fmax(rate, stiffness[k] / config.armature_kgm2[k]);
          } else {
            rate = std::fmax(rate, stiffness[k] / j_link[i]);
          }
        }
        const double h_cap = config.coupling == PlantCoupling::Decoupled ? config.substep_s
                                                                         : config.coupled_substep_s;
        const double h_limit = std::fmin(h_cap, stable_step(rate));
        const double count = std::fmax(1.0, std::ceil(length / h_limit - 1e-9));
        const double h = length / count;
        const Vec6 jm = to_vec(config.armature_kgm2);
        // d/dt (x, v, xm, vm) at offset s_in.
        const auto derivative = [&](double s_in, const Vec6& px, const Vec6& pv, const Vec6& pxm,
                                    const Vec6& pvm, Vec6& av, Vec6& avm) {
          const Vec6 cmd = drive_at(s_in) - dist;
          Vec6 gear = gear_k.cwiseProduct(pxm - px) + gear_c.cwiseProduct(pvm - pv);
          if (half_play > 0.0) {
            // Backlash: no gear torque within ±half_play of deflection, the spring beyond it.
            for (int i = 0; i < static_cast<int>(kNumJoints); ++i) {
              const double d = pxm[i] - px[i];
              const double beyond = d > half_play    ? d - half_play
                                    : d < -half_play ? d + half_play
                                                     : 0.0;
              gear[i] = beyond == 0.0 ? 0.0 : gear_k[i] * beyond + gear_c[i] * (pvm[i] - pv[i]);
            }
          }
          // Friction acts on the motor side of an elastic joint, on the joint of a rigid one.
          const Vec6 w =
              pvm.cwiseProduct(elastic_mask) + pv.cwiseProduct(Vec6::Ones() - elastic_mask);
          Vec6 resist = damping.cwiseProduct(w);
          if (coulomb) resist += friction(w);
          Vec6 f_link;
          Vec6 f_motor;
          for (int i = 0; i < static_cast<int>(kNumJoints); ++i) {
            const bool e = elastic_mask[i] != 0.0;
            f_link[i] = (e ? gear[i] : cmd[i] - resist[i]) + dist[i];
            f_motor[i] = e ? cmd[i] - resist[i] - gear[i] : 0.0;
          }
          if (!link_acceleration(px, pv, f_link, j_link, av)) return false;
          for (int i = 0; i < static_cast<int>(kNumJoints); ++i)
            avm[i] = elastic_mask[i] != 0.0 ? f_motor[i] / jm[i] : av[i];
          return true;
        };
        Vec6& y_vm = mv;
        Vec6& y_xm = mx;
        for (long step_k = 0; step_k < static_cast<long>(count); ++step_k) {
          const double s_in = static_cast<double>(step_k) * h;
          Vec6 k1v, k1m, k2v, k2m, k3v, k3m, k4v, k4m;
          if (!derivative(s_in, x, v, y_xm, y_vm, k1v, k1m)) return PlantStatus::NumericalError;
          const Vec6 x2 = x + 0.5 * h * v, v2 = v + 0.5 * h * k1v;
          const Vec6 xm2 = y_xm + 0.5 * h * y_vm, vm2 = y_vm + 0.5 * h * k1m;
          if (!derivative(s_in + 0.5 * h, x2, v2, xm2, vm2, k2v, k2m))
            return PlantStatus::NumericalError;
          const Vec6 x3 = x + 0.5 * h * v2, v3 = v + 0.5 * h * k2v;
          const Vec6 xm3 = y_xm + 0.5 * h * vm2, vm3 = y_vm + 0.5 * h * k2m;
          if (!derivative(s_in + 0.5 * h, x3, v3, xm3, vm3, k3v, k3m))
            return PlantStatus::NumericalError;
          const Vec6 x4 = x + h * v3, v4 = v + h * k3v;
          const Vec6 xm4 = y_xm + h * vm3, vm4 = y_vm + h * k3m;
          if (!derivative(s_in + h, x4, v4, xm4, vm4, k4v, k4m)) return PlantStatus::NumericalError;
          x += h / 6.0 * (v + 2.0 * v2 + 2.0 * v3 + v4);
          v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
          y_xm += h / 6.0 * (y_vm + 2.0 * vm2 + 2.0 * vm3 + vm4);
          y_vm += h / 6.0 * (k1m + 2.0 * k2m + 2.0 * k3m + k4m);
        }
        Vec6 a_m;
        if (!derivative(length, x, v, mx, mv, a_end, a_m)) return PlantStatus::NumericalError;
      } else if (length > 0.0 && config.coupling == PlantCoupling::Decoupled) {
        if (first) {
          if (config.inertia_update == InertiaUpdate::Fixed) {
            j_tick = to_array(fixed_mass.diagonal());
          } else {
            const JointVector diag = model.inertia_diagonal(q, *slot.data);
            for (std::size_t i = 0; i < kNumJoints; ++i)
              j_tick[i] = config.inertia_scale[i] * diag[i] + config.armature_kgm2[i];
          }
          double rate = wc;  // the fastest rate of the stiff terms, 1/s: max b_i / J_i, ω_c
          for (std::size_t i = 0; i < kNumJoints; ++i) {
            if (!(j_tick[i] > 0.0) || !std::isfinite(j_tick[i])) return PlantStatus::NumericalError;
            inv_j(static_cast<int>(i)) = 1.0 / j_tick[i];
            rate = std::fmax(rate, stiffness[i] / j_tick[i]);
          }
          // Substeps: whole steps of `substep_s` (or shorter, h·rate <= step_rate_limit), the
          // last one of each segment shortened to end exactly at its end.
          h_nominal = std::fmin(config.substep_s, stable_step(rate));
        }
        const double count = std::fmax(1.0, std::ceil(length / h_nominal - 1e-9));
        const auto steps = static_cast<long>(count);
        // θ̈ = (drive − b θ̇ − friction(θ̇)) / J is independent of θ.
        const auto accel = [&](double s_in, const Vec6& vel) -> Vec6 {
          Vec6 f = drive_at(s_in) - damping.cwiseProduct(vel);
          if (coulomb) f -= friction(vel);
          return f.cwiseProduct(inv_j);
        };
        double s_in = 0.0;
        for (long s = 0; s < steps; ++s) {
          const double h =
              s + 1 < steps ? h_nominal : length - h_nominal * static_cast<double>(steps - 1);
          const Vec6 k1v = accel(s_in, v);
          const Vec6 k1x = v;
          const Vec6 k2v = accel(s_in + 0.5 * h, v + 0.5 * h * k1v);
          const Vec6 k2x = v + 0.5 * h * k1v;
          const Vec6 k3v = accel(s_in + 0.5 * h, v + 0.5 * h * k2v);
          const Vec6 k3x = v + 0.5 * h * k2v;
          const Vec6 k4v = accel(s_in + h, v + h * k3v);
          const Vec6 k4x = v + h * k3v;
          x += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
          v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
          s_in += h;
        }
        a_end = accel(length, v);
      } else if (length > 0.0) {
        // k1 of the first substep also gives the tick's effective inertia and the step size.
        Vec6 k1_first;
        Vec6 diagonal;
        Mat6 mass;
        if (!coupled_acceleration(x, v, drive_at(0.0), k1_first, &diagonal, &mass))
          return PlantStatus::NumericalError;
        if (first) j_tick = to_array(diagonal);
        // Equal substeps no longer than coupled_substep_s, nor than the time in which a joint
        // moving with the segment's initial q̇ and q̈ covers coupled_step_rad (|q̇| h + ½ |q̈| h² =
        // θ, in its cancellation-free form h = 2θ / (|q̇| + √(q̇² + 2 |q̈| θ))): RK4's error grows
        // with how far the state moves through M(q), C and g within a step, so slow motion takes
        // long steps and fast motion short ones. At most kMaxCoupledSubsteps, so a wild state
        // cannot stall the tick; the bounds that follow from the configuration
        // (coupled_substep_s, the stiffness bound h·rate <= step_rate_limit) are always met.
        const double h_config =
            std::fmin(config.coupled_substep_s, stable_step(std::fmax(wc, coupled_rate(mass))));
        double h_max = std::numeric_limits<double>::infinity();
        const double theta = config.coupled_step_rad;
        if (std::isfinite(theta)) {
          for (int i = 0; i < static_cast<int>(kNumJoints); ++i) {
            const double speed = std::fabs(v[i]);
            const double h_i =
                2.0 * theta /
                (speed + std::sqrt(speed * speed + 2.0 * std::fabs(k1_first[i]) * theta));
            h_max = std::fmin(h_max, h_i);
          }
        }
        const double coupled_steps =
            std::fmax(std::fmax(1.0, std::ceil(length / h_config - 1e-9)),
                      std::fmin(kMaxCoupledSubsteps, std::ceil(length / h_max - 1e-9)));
        const double h = length / coupled_steps;
        for (long s = 0; s < static_cast<long>(coupled_steps); ++s) {
          const double s_in = static_cast<double>(s) * h;
          Vec6 k1v, k2v, k3v, k4v;
          if (s == 0) {
            k1v = k1_first;
          } else if (!coupled_acceleration(x, v, drive_at(s_in), k1v)) {
            return PlantStatus::NumericalError;
          }
          const Vec6 k1x = v;
          const Vec6 k2x = v + 0.5 * h * k1v;
          if (!coupled_acceleration(x + 0.5 * h * k1x, k2x, drive_at(s_in + 0.5 * h), k2v))
            return PlantStatus::NumericalError;
          const Vec6 k3x = v + 0.5 * h * k2v;
          if (!coupled_acceleration(x + 0.5 * h * k2x, k3x, drive_at(s_in + 0.5 * h), k3v))
            return PlantStatus::NumericalError;
          const Vec6 k4x = v + h * k3v;
          if (!coupled_acceleration(x + h * k3x, k4x, drive_at(s_in + h), k4v))
            return PlantStatus::NumericalError;
          x += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
          v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        }
      }
      if (length > 0.0) first = false;
      drive_end = drive_at(length);
      if (wc > 0.0) lag = u + (lag - u) * std::exp(-wc * length);
      if (t1 >= dt) break;
      // The next command arrives.
      command = delayed(static_cast<std::size_t>(next_command)).torque_nm;
      --next_command;
      t0 = t1;
      next_switch = arrival(next_command);
    }
    if (!x.allFinite() || !v.allFinite() || !a_end.allFinite()) return PlantStatus::NumericalError;
    if (elastic && !(mx.allFinite() && mv.allFinite())) return PlantStatus::NumericalError;
    xm = mx;
    vm = mv;

    q = to_array(x);
    qd = to_array(v);
    qdd = to_array(a_end);
    // The coupled q̈ at the end of the tick costs a full dynamics evaluation (a fifth of a 10 ms
    // tick's): acceleration() computes it when asked.
    qdd_pending = config.coupling == PlantCoupling::Coupled && !elastic;
    qdd_drive = drive_end;
    inertia = j_tick;
    applied = wc > 0.0 ? to_array(lag) : command;
    lag_torque = wc > 0.0 ? to_array(lag) : JointVector{};
    saturated = sat;
    time += dt;
    xm_out = to_array(xm);
    vm_out = to_array(vm);
    if (encoder_step > 0.0) {
      // The encoder is on the motor side (the two-mass joint's xm; the joint itself when rigid).
      const JointVector reading = quantised(elastic ? to_array(xm) : q);
      for (std::size_t i = 0; i < kNumJoints; ++i)
        measured_qd[i] = (reading[i] - measured_q[i]) / dt;
      measured_q = reading;
    }
    return any ? PlantStatus::Saturated : PlantStatus::Ok;
  }

  const JointVector& acceleration() const noexcept {
    if (qdd_pending) {
      Vec6 a;
      qdd = coupled_acceleration(to_vec(q), to_vec(qd), qdd_drive, a)
                ? to_array(a)
                : to_array(Vec6::Constant(std::numeric_limits<double>::quiet_NaN()));
      qdd_pending = false;
    }
    return qdd;
  }

  RobotModel model;
  DataSlot slot;  // the solvers' workspace for `model`
  PlantConfig config;
  bool valid = false;
  JointVector limit{};
  Vec6 sqrt_scale = Vec6::Ones();
  JointVector stiffness{};   // see the constructor
  bool stiff = false;        // any stiffness > 0
  bool coulomb = false;      // any Coulomb or Stribeck friction
  double lag_rate = 0.0;     // ω_c = 2π torque_bandwidth_hz, 1/s; 0: an ideal current loop
  JointVector lag_torque{};  // the current loop's output torque, N·m
  // The delay line: the last kDelayCommands commands, newest at delay_head.
  std::array<DelayedCommand, kDelayCommands> delay_line{};
  std::size_t delay_head = 0;
  std::size_t delay_count = 0;
  // The encoder: its resolution (rad; 0 = ideal) and the readings of the last step.
  double encoder_step = 0.0;
  JointVector measured_q{};
  JointVector measured_qd{};
  // The two-mass joint (joint_resonance_hz): which joints are elastic (1) or rigid (0), the gear's
  // stiffness (N·m/rad) and damping (N·m·s/rad), and the motor side's angle and velocity.
  bool elastic = false;
  double half_play = 0.0;  // half the backlash, rad
  Vec6 elastic_mask = Vec6::Zero();
  Vec6 gear_k = Vec6::Zero();
  Vec6 gear_c = Vec6::Zero();
  Vec6 xm = Vec6::Zero();
  Vec6 vm = Vec6::Zero();
  JointVector xm_out{};
  JointVector vm_out{};
  Mat6 fixed_mass = Mat6::Identity();
  JointVector q{};
  JointVector qd{};
  // acceleration(): cached; in coupled mode evaluated from (q, qd, qdd_drive) on first request.
  mutable JointVector qdd{};
  mutable bool qdd_pending = false;
  Vec6 qdd_drive = Vec6::Zero();
  JointVector inertia{};
  JointVector applied{};
  std::array<bool, kNumJoints> saturated{};
  double time = 0.0;
};

JointPlant::JointPlant(const RobotModel& model, const PlantConfig& config)
    : impl_(std::make_unique<Impl>(model, config)) {}
JointPlant::JointPlant(const JointPlant& other) : impl_(std::make_unique<Impl>(*other.impl_)) {
  impl_->slot.data.emplace(impl_->model);
}
JointPlant::JointPlant(JointPlant&& other) noexcept = default;
JointPlant& JointPlant::operator=(const JointPlant& other) {
  if (this != &other) {
    impl_ = std::make_unique<Impl>(*other.impl_);
    impl_->slot.data.emplace(impl_->model);
  }
  return *this;
}
JointPlant& JointPlant::operator=(JointPlant&& other) noexcept = default;
JointPlant::~JointPlant() = default;

bool JointPlant::valid() const noexcept {
  return impl_->valid;
}
void JointPlant::reset(const JointVector& q_rad, const JointVector& qd_rad_s) noexcept {
  impl_->reset(q_rad, qd_rad_s);
}
PlantStatus JointPlant::step(const JointVector& torque_nm, double dt_s,
                             const JointVector& disturbance_nm) noexcept {
  return impl_->step(torque_nm, dt_s, disturbance_nm);
}
const JointVector& JointPlant::position() const noexcept {
  return impl_->q;
}
const JointVector& JointPlant::velocity() const noexcept {
  return impl_->qd;
}
const JointVector& JointPlant::measured_position() const noexcept {
  if (impl_->encoder_step > 0.0) return impl_->measured_q;
  return impl_->elastic ? impl_->xm_out : impl_->q;
}
const JointVector& JointPlant::measured_velocity() const noexcept {
  if (impl_->encoder_step > 0.0) return impl_->measured_qd;
  return impl_->elastic ? impl_->vm_out : impl_->qd;
}
const JointVector& JointPlant::motor_position() const noexcept {
  return impl_->elastic ? impl_->xm_out : impl_->q;
}
const JointVector& JointPlant::acceleration() const noexcept {
  return impl_->acceleration();
}
const JointVector& JointPlant::inertia() const noexcept {
  return impl_->inertia;
}
const JointVector& JointPlant::applied_torque() const noexcept {
  return impl_->applied;
}
const std::array<bool, kNumJoints>& JointPlant::saturated() const noexcept {
  return impl_->saturated;
}
double JointPlant::time_s() const noexcept {
  return impl_->time;
}
const PlantConfig& JointPlant::config() const noexcept {
  return impl_->config;
}
const RobotModel& JointPlant::model() const noexcept {
  return impl_->model;
}

}  // namespace fuzzypid::robot
