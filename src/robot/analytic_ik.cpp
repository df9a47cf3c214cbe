// Closed-form IK of the ER50-C20; the derivation is in analytic_ik.hpp.
#include "fuzzypid/robot/analytic_ik.hpp"

#include <cmath>

#include "fuzzypid/robot/ik.hpp"
#include "fuzzypid/robot/robot_model.hpp"

namespace fuzzypid::robot {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;
// Below this distance of the wrist center from the J1 axis (m), or this |sin q5|, the pose is
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

// The arm (q1, q2, q3) of one branch pair; the wrist adds two (q4, q5, q6) to it.
struct Arm {
  double q1, q2, q3;
};

// The arm solutions of the wrist center p (up to 4: two q1 times elbow up / down), in branch
// order. A wrist center on the J1 axis takes seed_q1 and sets `singular`.
std::size_t arm_branches(const DhParameters& dh, const Eigen::Vector3d& p, double seed_q1,
                         Arm (&arms)[4], bool& singular) noexcept {
  const double px = p.x();
  const double py = p.y();
  const double pz = p.z();

  double q1_candidates[2];
  if (std::hypot(px, py) < kSingularEps) {  // wrist center on the J1 axis: q1 is free
    singular = true;
    q1_candidates[0] = wrap(seed_q1);
  } else {
    q1_candidates[0] = std::atan2(py, px);
  }
  q1_candidates[1] = wrap(q1_candidates[0] + kPi);  // reaching backwards over the base

  const double rho = std::hypot(dh.a3_m, dh.d4_m);
  const double phi = std::atan2(dh.d4_m, dh.a3_m);
  std::size_t count = 0;
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
      arms[count++] = {q1, q2, q3};
    }
  }
  return count;
}

// R36 = R03^T R of one arm, written as RotZ(q4) RotY(-q5) RotZ(q6).
Eigen::Matrix3d wrist_rotation(const Arm& arm, const Eigen::Matrix3d& rotation) noexcept {
  // Rotation of frame 4 relative to the J4 axis convention: R36 = RotX(-90) RotZ(q4) RotY(-q5)
  // RotZ(q6), so RotX(-90)^T = RotX(90) is applied on the left.
  Eigen::Matrix3d rot_x_90;
  rot_x_90 << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  const JointVector q = {arm.q1, arm.q2, arm.q3, 0.0, 0.0, 0.0};
  return rot_x_90 * dh_rotation_0_3(q).transpose() * rotation;
}

// |sin q5| of the wrist rotation w; below kSingularEps the wrist is singular.
double wrist_s5(const Eigen::Matrix3d& w) noexcept {
  return std::hypot(w(0, 2), w(1, 2));
}

// (q4, q5, q6) of wrist branch sigma (+1 or -1) of w, q5 not yet wrapped. At a wrist singularity
// q4 is the seed's (plus pi for sigma = -1).
void wrist_branch(const Eigen::Matrix3d& w, double s5_abs, double sigma, double seed_q4, double& q4,
                  double& q5, double& q6) noexcept {
  // w = RotZ(q4) RotY(-q5) RotZ(q6): w13 = -c4 s5, w23 = -s4 s5, w33 = c5, w31 = s5 c6,
  // w32 = -s5 s6.
  if (s5_abs < kSingularEps) {
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
  Arm arms[4];
  const std::size_t num_arms = arm_branches(dh, target.position_m, seed_q1, arms, singular);
  for (std::size_t a = 0; a < num_arms; ++a) {
    const Arm& arm = arms[a];
    const Eigen::Matrix3d w = wrist_rotation(arm, target.rotation);
    const double s5_abs = wrist_s5(w);
    if (s5_abs < kSingularEps) singular = true;
    for (double sigma : {1.0, -1.0}) {
      double q4 = 0.0;
      double q5 = 0.0;
      double q6 = 0.0;
      wrist_branch(w, s5_abs, sigma, seed_q4, q4, q5, q6);
      result.solutions[result.count++] = {arm.q1, arm.q2, arm.q3, q4, wrap(q5), q6};
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
  RobotData data(model);
  for (const JointVector& q : probes) {
    const Pose a = model.forward_kinematics(q, data);
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

// The same choice as evaluating every branch of branches() and keeping, in branch order, the first
// with the smallest distance to the seed, but without computing branches that cannot win. The
// squared distance is a sum of non-negative terms added in joint order, so the sum over q1..q3
// of an arm is a lower bound of the distance of both its wrist branches (rounding is monotone).
// Arms are visited by increasing lower bound; an arm whose bound exceeds the best distance, or
// equals it with a later branch index, is skipped (its branches could at best tie and lose on
// index). Its wrist rotation is still formed, for the Singular status.
IkStatus AnalyticIk::solve(const Pose& target, const JointVector& seed,
                           JointVector& out) const noexcept {
  for (double s : seed) {
    if (!std::isfinite(s)) return IkStatus::InvalidInput;
  }
  if (!is_valid_pose(target)) return IkStatus::InvalidInput;
  bool singular = false;
  Arm arms[4];
  const std::size_t num_arms = arm_branches(dh_, target.position_m, seed[0], arms, singular);
  if (num_arms == 0) return IkStatus::Unreachable;

  struct Partial {
    std::size_t arm;
    double bound;  // distance over q1..q3
    JointVector candidate;
    Eigen::Matrix3d w;
    double s5_abs;
  };
  Partial partials[4];
  std::size_t num_partials = 0;
  for (std::size_t a = 0; a < num_arms; ++a) {
    const Eigen::Matrix3d w = wrist_rotation(arms[a], target.rotation);
    const double s5_abs = wrist_s5(w);
    if (s5_abs < kSingularEps) singular = true;
    const double q[3] = {arms[a].q1, arms[a].q2, arms[a].q3};
    Partial p{a, 0.0, {}, w, s5_abs};
    bool ok = true;
    for (std::size_t j = 0; j < 3 && ok; ++j) {
      ok = shift_into_limits(q[j], seed[j], lower_[j], upper_[j], p.candidate[j]);
      const double dj = p.candidate[j] - seed[j];
      p.bound += dj * dj;
    }
    if (!ok) continue;  // neither wrist branch of this arm is within the limits
    // Insertion by (bound, arm): at most 4 entries.
    std::size_t at = num_partials++;
    while (at > 0 && partials[at - 1].bound > p.bound) {
      partials[at] = partials[at - 1];
      --at;
    }
    partials[at] = p;
  }

  bool found = false;
  double best_distance = 0.0;
  std::size_t best_index = 0;
  JointVector best{};
  for (std::size_t k = 0; k < num_partials; ++k) {
    const Partial& p = partials[k];
    if (found && (p.bound > best_distance || (p.bound == best_distance && 2 * p.arm > best_index)))
      break;  // later entries have bounds at least as large
    for (std::size_t b = 0; b < 2; ++b) {
      const std::size_t index = 2 * p.arm + b;
      double q4 = 0.0;
      double q5 = 0.0;
      double q6 = 0.0;
      wrist_branch(p.w, p.s5_abs, b == 0 ? 1.0 : -1.0, seed[3], q4, q5, q6);
      const double q[3] = {q4, wrap(q5), q6};
      JointVector candidate = p.candidate;
      bool ok = true;
      double distance = p.bound;
      for (std::size_t j = 3; j < kNumJoints && ok; ++j) {
        ok = shift_into_limits(q[j - 3], seed[j], lower_[j], upper_[j], candidate[j]);
        const double dj = candidate[j] - seed[j];
        distance += dj * dj;
      }
      if (ok && (!found || distance < best_distance ||
                 (distance == best_distance && index < best_index))) {
        found = true;
        best_distance = distance;
        best_index = index;
        best = candidate;
      }
    }
  }
  if (!found) return IkStatus::JointLimits;
  out = best;
  return singular ? IkStatus::Singular : IkStatus::Ok;
}

}  // namespace fuzzypid::robot
