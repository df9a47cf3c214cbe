// Closed-form inverse kinematics of the ER50-C20 (Pieper's method for a 6R arm with a spherical
// wrist), on the modified D-H model of dh_parameters.hpp.
//
// The tip is the wrist center, so the target position alone fixes q1..q3:
//   q1 = atan2(py, px) or that + pi (arm reaching backwards over the base);
//   with r = c1 px + s1 py, m = r - a1, n = d1 - pz:
//     a3 c3 - d4 s3 = k,  k = (m² + n² - a2² - a3² - d4²) / (2 a2)    (the paper's k, section 2.2)
//     q3 = -atan2(d4, a3) ± acos(k / sqrt(a3² + d4²))                     (elbow up / down)
//     q2 = atan2(n, m) - atan2(v, u),  u = a2 + a3 c3 - d4 s3, v = a3 s3 + d4 c3;
// then R36 = R03ᵀ R gives q4..q6 as Z-Y-Z Euler angles with the middle angle -q5, two branches.
// That is up to 8 solutions. Each angle is shifted by multiples of 2 pi to the value nearest the
// seed within the limits (J1, J4 and J6 span 360° or more, Table 1).
//
// Singularities: the wrist center on the J1 axis leaves q1 free and sin(q5) = 0 leaves only q4 + q6
// (or q4 - q6) determined; the solver then keeps the seed's q1 or q4, returns a solution that still
// reaches the target and reports IkStatus::Singular.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>

#include "fuzzypid/robot/dh_parameters.hpp"
#include "fuzzypid/robot/ik_status.hpp"
#include "fuzzypid/robot/types.hpp"

namespace fuzzypid::robot {

class RobotModel;

// Up to eight branches of one target, before joint limits are applied. Each branch is wrapped to
// (-pi, pi]; `within_limits[k]` says whether some 2 pi shift of branch k fits the limits.
struct IkBranches {
  std::array<JointVector, 8> solutions{};
  std::array<bool, 8> within_limits{};
  std::size_t count = 0;
  IkStatus status = IkStatus::Unreachable;  // Ok, Singular, Unreachable or InvalidInput
};

class AnalyticIk {
 public:
  // Table 1 geometry and the given limits (rad).
  AnalyticIk(const DhParameters& dh, const JointVector& lower_rad, const JointVector& upper_rad);

  // Uses the model's joint limits after checking that the model's forward kinematics is the D-H
  // model `dh` (to 1e-9 m / rad at a few configurations). Returns nullopt (and a reason in *error
  // when error is non-null) for any other geometry.
  [[nodiscard]] static std::optional<AnalyticIk> from_model(const RobotModel& model,
                                                            const DhParameters& dh = er50_c20_dh(),
                                                            std::string* error = nullptr);

  // The solution nearest the seed (Euclidean distance in joint space) among those within the
  // limits. `out` is written only when the status is Ok or Singular. Allocation-free.
  [[nodiscard]] IkStatus solve(const Pose& target, const JointVector& seed,
                               JointVector& out) const noexcept;

  // Every branch, wrapped to (-pi, pi], without choosing one.
  [[nodiscard]] IkBranches solve_all(const Pose& target) const noexcept;

  const DhParameters& dh() const noexcept { return dh_; }
  const JointVector& lower_limits_rad() const noexcept { return lower_; }
  const JointVector& upper_limits_rad() const noexcept { return upper_; }

 private:
  DhParameters dh_;
  JointVector lower_;
  JointVector upper_;
};

}  // namespace fuzzypid::robot
