// Closed-form IK of the ER50-C20; the derivation is in analytic_ik.hpp.
#include "fuzzypid/robot/analytic_ik.hpp"

#include <cmath>

#include "fuzzypid/robot/ik.hpp"
#include "fuzzypid/robot/robot_model.hpp"

namespace fuzzypid::robot {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;
// Below this distance of the wrist centre from the J1 axis (m), or this |sin q5|, the pose is
// treated as singular. Both are far below any physical tolerance.
constexpr double kSingularEps = 1e-12;
// Round-off allowed beyond the reach sphere (relative) and beyond a joint limit (rad).
constexpr double kReachEps = 1e-12;
constexpr double kLimitEps = 1e-10;

double wrap(double a) noexcept {
  a = std::remainder(a, kTwoPi);  // [-pi, pi]
  return a <= -kPi ? a + kTwoPi : a;
}

// The 2 pi shift of `value` within [lo, hi] nearest `seed`; false when none fits. A value within
// kLimitEps outside a limit is clamped onto it.
bool shift_into_limits(double value, double seed, double lo, double hi, double& out) noexcept {
  if (!std::isfinite(lo) || !std::isfinite(hi)) {
    out = value + kTwoPi * std::round((seed - value) / kTwoPi);
    if (out < lo) out += kTwoPi;
    if (out > hi) out -= kTwoPi;
    return true;
  }
  const double k_min = std::ceil((lo - kLimitEps - value) / kTwoPi);
  const double k_max = std::floor((hi + kLimitEps - value) / kTwoPi);
  bool found = false;
  double best = 0.0;
  for (double k = k_min; k <= k_max; k += 1.0) {
    const double candidate = std::fmin(std::fmax(value + kTwoPi * k, lo), hi);
    if (!found || std::fabs(candidate - seed) < std::fabs(best - seed)) best = candidate;
    found = true;
  }
  if (found) out = best;
  return found;
}

bool finite(const Pose& p) noexcept {
  return p.position_m.allFinite() && p.rotation.allFinite();
}

// All branches; in singular configurations the free joint takes seed_q1 / seed_q4.
IkBranches branches(const DhParameters& dh, const Pose& target, double seed_q1,
                    double seed_q4) noexcept {
  IkBranches result;
  if (!finite(target)) {
    result.status = IkStatus::InvalidInput;
    return result;
  }
  bool singular = false;
  const double px = target.position_m.x();
  const double py = target.position_m.y();
  const double pz = target.position_m.z();

  double q1_candidates[2];
  if (std::hypot(px, py) < kSingularEps) {  // wrist centre on the J1 axis: q1 is free
    singular = true;
    q1_candidates[0] = wrap(seed_q1);
  } else {
    q1_candidates[0] = std::atan2(py, px);
  }
  q1_candidates[1] = wrap(q1_candidates[0] + kPi);  // reaching backwards over the base

  const double rho = std::hypot(dh.a3_m, dh.d4_m);
  const double phi = std::atan2(dh.d4_m, dh.a3_m);
  // Rotation of frame 4 relative to the J4 axis convention: R36 = RotX(-90) RotZ(q4) RotY(-q5)
  // RotZ(q6), so RotX(-90)ᵀ = RotX(90) is applied on the left.
  Eigen::Matrix3d rot_x_90;
  rot_x_90 << 1, 0, 0, 0, 0, -1, 0, 1, 0;

  for (double q1 : q1_candidates) {
    const double c1 = std::cos(q1);
    const double s1 = std::sin(q1);
    const double m = c1 * px + s1 * py - dh.a1_m;
    const double n = dh.d1_m - pz;
    const double k = (m * m + n * n - dh.a2_m * dh.a2_m - dh.a3_m * dh.a3_m - dh.d4_m * dh.d4_m) /
                     (2.0 * dh.a2_m);
    double ratio = k / rho;
    if (std::fabs(ratio) > 1.0 + kReachEps) continue;
    ratio = std::fmax(-1.0, std::fmin(1.0, ratio));
    const double elbow = std::acos(ratio);
    for (double sign : {1.0, -1.0}) {
      const double q3 = wrap(-phi + sign * elbow);
      const double c3 = std::cos(q3);
      const double s3 = std::sin(q3);
      const double u = dh.a2_m + dh.a3_m * c3 - dh.d4_m * s3;
      const double v = dh.a3_m * s3 + dh.d4_m * c3;
      const double q2 = wrap(std::atan2(n, m) - std::atan2(v, u));

      const JointVector arm = {q1, q2, q3, 0.0, 0.0, 0.0};
      const Eigen::Matrix3d w = rot_x_90 * dh_rotation_0_3(arm).transpose() * target.rotation;
      // w = RotZ(q4) RotY(-q5) RotZ(q6): w13 = -c4 s5, w23 = -s4 s5, w33 = c5, w31 = s5 c6,
      // w32 = -s5 s6.
      const double s5_abs = std::hypot(w(0, 2), w(1, 2));
      for (double sigma : {1.0, -1.0}) {
        double q4 = 0.0;
        double q5 = 0.0;
        double q6 = 0.0;
        if (s5_abs < kSingularEps) {
          singular = true;
          q4 = wrap(seed_q4 + (sigma > 0 ? 0.0 : kPi));
          if (w(2, 2) > 0.0) {  // q5 = 0: w = RotZ(q4 + q6)
            q5 = 0.0;
            q6 = wrap(std::atan2(w(1, 0), w(0, 0)) - q4);
          } else {  // q5 = pi: w11 = -cos(q4 - q6), w21 = -sin(q4 - q6)
            q5 = kPi;
            q6 = wrap(q4 - std::atan2(-w(1, 0), -w(0, 0)));
          }
        } else {
          q5 = std::atan2(sigma * s5_abs, w(2, 2));
          q4 = std::atan2(-sigma * w(1, 2), -sigma * w(0, 2));
          q6 = std::atan2(-sigma * w(2, 1), sigma * w(2, 0));
        }
        result.solutions[result.count++] = {q1, q2, q3, q4, wrap(q5), q6};
      }
    }
  }
  if (result.count == 0) {
    result.status = IkStatus::Unreachable;
  } else {
    result.status = singular ? IkStatus::Singular : IkStatus::Ok;
  }
  return result;
}

}  // namespace

AnalyticIk::AnalyticIk(const DhParameters& dh, const JointVector& lower_rad,
                       const JointVector& upper_rad)
    : dh_(dh), lower_(lower_rad), upper_(upper_rad) {}

std::optional<AnalyticIk> AnalyticIk::from_model(const RobotModel& model, const DhParameters& dh,
                                                 std::string* error) {
  // Configurations that exercise every joint, including all twists and offsets.
  const JointVector probes[] = {{0, 0, 0, 0, 0, 0},
                                {0.3, -0.4, 0.5, -0.6, 0.7, -0.8},
                                {-1.1, 0.9, -0.7, 1.3, -1.5, 2.0},
                                {2.5, -1.9, 1.6, -2.2, 0.4, 3.0}};
  for (const JointVector& q : probes) {
    const Pose a = model.forward_kinematics(q);
    const Pose b = dh_forward_kinematics(dh, q);
    const double dp = (a.position_m - b.position_m).norm();
    const double dr = (a.rotation - b.rotation).cwiseAbs().maxCoeff();
    if (!(dp < 1e-9 && dr < 1e-9)) {
      if (error != nullptr) {
        *error = "the model's kinematics differ from the Table 1 D-H geometry (by " +
                 std::to_string(dp) + " m at a probe configuration); no closed form";
      }
      return std::nullopt;
    }
  }
  return AnalyticIk(dh, model.lower_limits_rad(), model.upper_limits_rad());
}

IkBranches AnalyticIk::solve_all(const Pose& target) const noexcept {
  IkBranches b = branches(dh_, target, 0.0, 0.0);
  for (std::size_t k = 0; k < b.count; ++k) {
    bool ok = true;
    for (std::size_t j = 0; j < kNumJoints && ok; ++j) {
      double shifted = 0.0;
      ok = shift_into_limits(b.solutions[k][j], b.solutions[k][j], lower_[j], upper_[j], shifted);
    }
    b.within_limits[k] = ok;
  }
  return b;
}

IkStatus AnalyticIk::solve(const Pose& target, const JointVector& seed,
                           JointVector& out) const noexcept {
  for (double s : seed) {
    if (!std::isfinite(s)) return IkStatus::InvalidInput;
  }
  if (!is_valid_pose(target)) return IkStatus::InvalidInput;
  const IkBranches b = branches(dh_, target, seed[0], seed[3]);
  if (b.count == 0) return b.status;

  bool found = false;
  double best_distance = 0.0;
  JointVector best{};
  for (std::size_t k = 0; k < b.count; ++k) {
    JointVector candidate{};
    bool ok = true;
    double distance = 0.0;
    for (std::size_t j = 0; j < kNumJoints && ok; ++j) {
      ok = shift_into_limits(b.solutions[k][j], seed[j], lower_[j], upper_[j], candidate[j]);
      const double dj = candidate[j] - seed[j];
      distance += dj * dj;
    }
    if (ok && (!found || distance < best_distance)) {
      found = true;
      best_distance = distance;
      best = candidate;
    }
  }
  if (!found) return IkStatus::JointLimits;
  out = best;
  return b.status;
}

}  // namespace fuzzypid::robot
