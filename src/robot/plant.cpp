// JointPlant: the equations are documented in plant.hpp.
#include "fuzzypid/robot/plant.hpp"

#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "rigid_body_dynamics.hpp"

namespace fuzzypid::robot {
namespace {

constexpr double kMaxCoupledSubsteps = 1000.0;

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

}  // namespace

class JointPlant::Impl {
 public:
  Impl(const RobotModel& m, const PlantConfig& c) : model(m), config(c) {
    limit = config.torque_limit_nm.value_or(model.effort_limits_nm());
    valid = std::isfinite(config.substep_s) && config.substep_s > 0.0 &&
            std::isfinite(config.coupled_substep_s) && config.coupled_substep_s > 0.0 &&
            config.coupled_step_rad > 0.0 && all_non_negative(config.armature_kgm2) &&
            all_finite(config.armature_kgm2) && all_non_negative(config.inertia_scale) &&
            all_finite(config.inertia_scale) && all_non_negative(config.damping_nms) &&
            all_finite(config.damping_nms) && all_non_negative(limit) &&
            std::isfinite(config.gravity_m_s2) &&
            (!config.fixed_configuration_rad || all_finite(*config.fixed_configuration_rad));
    valid = valid && std::isfinite(config.step_rate_limit) && config.step_rate_limit > 0.0;
    sqrt_scale = to_vec(config.inertia_scale).cwiseSqrt();
    // The slopes of the torques that oppose velocity, N·m·s/rad: what makes the plant stiff.
    stiffness = config.damping_nms;
    for (double b : stiffness)
      stiff = stiff || b > 0.0;
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
    // Decoupled J_i = s_i M_ii + armature_i is the diagonal of the effective mass matrix.
    fixed_mass = effective_mass(config.fixed_configuration_rad.value_or(q0));
    inertia = to_array(config.inertia_update == InertiaUpdate::Fixed
                           ? Vec6(fixed_mass.diagonal())
                           : Vec6(effective_mass(q0).diagonal()));
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
  Mat6 effective_mass(const JointVector& at) const noexcept {
    Mat6 m = sqrt_scale.asDiagonal() * model.mass_matrix(at) * sqrt_scale.asDiagonal();
    m.diagonal() += to_vec(config.armature_kgm2);
    return m;
  }

  // q̈ for the coupled model at (x, v), from the fixed-size RNEA/CRBA over the model's chain;
  // false if M_eff is not positive definite. `diagonal`, when given, receives diag(M_eff).
  bool coupled_acceleration(const Vec6& x, const Vec6& v, const Vec6& drive, Vec6& a,
                            Vec6* diagonal = nullptr, Mat6* mass = nullptr) const noexcept {
    const detail::RigidBodyDynamics& dynamics = detail::dynamics_of(model);
    const double g = config.gravity ? config.gravity_m_s2 : 0.0;
    Mat6 m;
    Vec6 bias;
    if (config.inertia_update == InertiaUpdate::Fixed) {
      m = fixed_mass;
      bias = dynamics.bias(x, v, g);
    } else {
      dynamics.mass_and_bias(x, v, g, m, bias);
      m = sqrt_scale.asDiagonal() * m * sqrt_scale.asDiagonal();
      m.diagonal() += to_vec(config.armature_kgm2);
    }
    if (diagonal != nullptr) *diagonal = m.diagonal();
    if (mass != nullptr) *mass = m;
    const Vec6 rhs = drive - to_vec(config.damping_nms).cwiseProduct(v) - bias;
    const Eigen::LLT<Mat6> llt(m);
    if (llt.info() != Eigen::Success) return false;
    a = llt.solve(rhs);
    return true;
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
    const Vec6 drive = to_vec(clamped) + to_vec(disturbance);
    const Vec6 damping = to_vec(config.damping_nms);

    Vec6 x = to_vec(q);
    Vec6 v = to_vec(qd);
    Vec6 a_end = Vec6::Zero();
    JointVector j_tick{};

    if (config.coupling == PlantCoupling::Decoupled) {
      Vec6 inv_j;
      if (config.inertia_update == InertiaUpdate::Fixed) {
        j_tick = to_array(fixed_mass.diagonal());
      } else {
        const JointVector diag = model.inertia_diagonal(q);
        for (std::size_t i = 0; i < kNumJoints; ++i)
          j_tick[i] = config.inertia_scale[i] * diag[i] + config.armature_kgm2[i];
      }
      double rate = 0.0;  // the fastest rate of the linear terms, 1/s: max b_i / J_i
      for (std::size_t i = 0; i < kNumJoints; ++i) {
        if (!(j_tick[i] > 0.0) || !std::isfinite(j_tick[i])) return PlantStatus::NumericalError;
        inv_j(static_cast<int>(i)) = 1.0 / j_tick[i];
        rate = std::fmax(rate, stiffness[i] / j_tick[i]);
      }
      // Substeps: whole steps of `substep_s` (or shorter, h·rate <= step_rate_limit), the last one
      // shortened to end exactly at dt.
      const double h_nominal = std::fmin(config.substep_s, stable_step(rate));
      const double count = std::fmax(1.0, std::ceil(dt / h_nominal - 1e-9));
      const auto steps = static_cast<long>(count);
      // θ̈ = (drive − b θ̇) / J is linear in θ̇ and independent of θ.
      const auto accel = [&](const Vec6& vel) -> Vec6 {
        return (drive - damping.cwiseProduct(vel)).cwiseProduct(inv_j);
      };
      for (long s = 0; s < steps; ++s) {
        const double h =
            s + 1 < steps ? h_nominal : dt - h_nominal * static_cast<double>(steps - 1);
        const Vec6 k1v = accel(v);
        const Vec6 k1x = v;
        const Vec6 k2v = accel(v + 0.5 * h * k1v);
        const Vec6 k2x = v + 0.5 * h * k1v;
        const Vec6 k3v = accel(v + 0.5 * h * k2v);
        const Vec6 k3x = v + 0.5 * h * k2v;
        const Vec6 k4v = accel(v + h * k3v);
        const Vec6 k4x = v + h * k3v;
        x += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
        v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
      }
      a_end = accel(v);
    } else {
      // k1 of the first substep also gives the tick's effective inertia and the step size.
      Vec6 k1_first;
      Vec6 diagonal;
      Mat6 mass;
      if (!coupled_acceleration(x, v, drive, k1_first, &diagonal, &mass))
        return PlantStatus::NumericalError;
      j_tick = to_array(diagonal);
      // Equal substeps no longer than coupled_substep_s, nor than the time in which a joint moving
      // with the tick's initial q̇ and q̈ covers coupled_step_rad (|q̇| h + ½ |q̈| h² = θ, in its
      // cancellation-free form h = 2θ / (|q̇| + √(q̇² + 2 |q̈| θ))): RK4's error grows with how far
      // the state moves through M(q), C and g within a step, so slow motion takes long steps and
      // fast motion short ones. At most kMaxCoupledSubsteps, so a wild state cannot stall the tick;
      // the bounds that follow from the configuration (coupled_substep_s, the stiffness bound
      // h·rate <= step_rate_limit) are always met.
      const double h_config = std::fmin(config.coupled_substep_s, stable_step(coupled_rate(mass)));
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
          std::fmax(std::fmax(1.0, std::ceil(dt / h_config - 1e-9)),
                    std::fmin(kMaxCoupledSubsteps, std::ceil(dt / h_max - 1e-9)));
      const double h = dt / coupled_steps;
      for (long s = 0; s < static_cast<long>(coupled_steps); ++s) {
        Vec6 k1v, k2v, k3v, k4v;
        if (s == 0) {
          k1v = k1_first;
        } else if (!coupled_acceleration(x, v, drive, k1v)) {
          return PlantStatus::NumericalError;
        }
        const Vec6 k1x = v;
        const Vec6 k2x = v + 0.5 * h * k1v;
        if (!coupled_acceleration(x + 0.5 * h * k1x, k2x, drive, k2v))
          return PlantStatus::NumericalError;
        const Vec6 k3x = v + 0.5 * h * k2v;
        if (!coupled_acceleration(x + 0.5 * h * k2x, k3x, drive, k3v))
          return PlantStatus::NumericalError;
        const Vec6 k4x = v + h * k3v;
        if (!coupled_acceleration(x + h * k3x, k4x, drive, k4v)) return PlantStatus::NumericalError;
        x += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
        v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
      }
    }
    if (!x.allFinite() || !v.allFinite() || !a_end.allFinite()) return PlantStatus::NumericalError;

    q = to_array(x);
    qd = to_array(v);
    qdd = to_array(a_end);
    // The coupled q̈ at the end of the tick costs a full dynamics evaluation (a fifth of a 10 ms
    // tick's): acceleration() computes it when asked.
    qdd_pending = config.coupling == PlantCoupling::Coupled;
    qdd_drive = drive;
    inertia = j_tick;
    applied = clamped;
    saturated = sat;
    time += dt;
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
  PlantConfig config;
  bool valid = false;
  JointVector limit{};
  Vec6 sqrt_scale = Vec6::Ones();
  JointVector stiffness{};  // see the constructor
  bool stiff = false;       // any stiffness > 0
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
JointPlant::JointPlant(const JointPlant& other) : impl_(std::make_unique<Impl>(*other.impl_)) {}
JointPlant::JointPlant(JointPlant&& other) noexcept = default;
JointPlant& JointPlant::operator=(const JointPlant& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
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
