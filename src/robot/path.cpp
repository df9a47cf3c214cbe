// Straight-line Cartesian path -> joint-space reference (section 6).
#include "fuzzypid/robot/path.hpp"

#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "fuzzypid/robot/dh_parameters.hpp"
#include "fuzzypid/robot/robot_model.hpp"

namespace fuzzypid::robot {

Eigen::Matrix3d paper_path_rotation() {
  return dh_forward_kinematics(er50_c20_dh(), kPaperStartJoints).rotation;
}

CartesianPathSpec paper_path_spec() {
  CartesianPathSpec spec;
  spec.start_m = Eigen::Vector3d(1350.0, 530.0, 1250.0) / 1000.0;  // A, section 6 (mm)
  spec.end_m = Eigen::Vector3d(1615.0, 240.0, 490.0) / 1000.0;     // B, section 6 (mm)
  spec.start_rotation = paper_path_rotation();
  spec.end_rotation = spec.start_rotation;
  spec.orientation = OrientationMode::Fixed;
  return spec;
}

JointPathResult plan_joint_path(const RobotModel& model, const CartesianPathSpec& spec,
                                IkSolver solver, const JointVector& seed) {
  const InverseKinematics ik(model);
  return plan_joint_path(ik, model, spec, solver, seed);
}

JointPathResult plan_joint_path(const InverseKinematics& ik, const RobotModel& model,
                                const CartesianPathSpec& spec, IkSolver solver,
                                const JointVector& seed) {
  JointPathResult r;
  const Pose start{spec.start_m, spec.start_rotation};
  const Pose end{spec.end_m, spec.end_rotation};
  if (spec.samples < 2 || !(spec.duration_s > 0.0) || !std::isfinite(spec.duration_s) ||
      !is_valid_pose(start) || !is_valid_pose(end) || !(spec.max_joint_step_rad > 0.0)) {
    r.status = PathStatus::InvalidSpec;
    r.message =
        "path spec needs >= 2 samples, a positive duration and step threshold, finite "
        "points and proper rotations";
    return r;
  }
  const Eigen::Quaterniond qa(spec.start_rotation);
  const Eigen::Quaterniond qb(spec.end_rotation);
  const std::size_t n = spec.samples;
  const double last = static_cast<double>(n - 1);
  r.time_s.reserve(n);
  r.poses.reserve(n);
  r.position_rad.reserve(n);

  JointVector previous = seed;
  for (std::size_t k = 0; k < n; ++k) {
    const double s = static_cast<double>(k) / last;
    Pose target;
    target.position_m = (1.0 - s) * spec.start_m + s * spec.end_m;
    target.rotation = spec.orientation == OrientationMode::Fixed
                          ? spec.start_rotation
                          : qa.slerp(s, qb).toRotationMatrix();
    r.time_s.push_back(spec.duration_s * s);
    r.poses.push_back(target);

    JointVector q{};
    const IkStatus status = ik.solve(solver, target, previous, q);
    if (status != IkStatus::Ok && status != IkStatus::Singular) {
      r.status = PathStatus::IkFailed;
      r.ik_status = status;
      r.first_failure = k;
      r.message = "sample " + std::to_string(k) + ": inverse kinematics " + to_string(status);
      return r;
    }
    if (k > 0) {
      for (std::size_t j = 0; j < kNumJoints; ++j) {
        const double step = std::fabs(q[j] - previous[j]);
        if (step > spec.max_joint_step_rad) {
          r.status = PathStatus::JointJump;
          r.first_failure = k;
          r.message = "sample " + std::to_string(k) + ": joint " + std::to_string(j + 1) +
                      " jumps by " + std::to_string(step) + " rad";
          return r;
        }
      }
    }
    r.position_rad.push_back(q);
    previous = q;
  }

  const double h = spec.duration_s / last;
  r.velocity_rad_s.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t lo = k == 0 ? 0 : k - 1;
    const std::size_t hi = k + 1 == n ? k : k + 1;
    const double span = h * static_cast<double>(hi - lo);
    for (std::size_t j = 0; j < kNumJoints; ++j) {
      const double v = (r.position_rad[hi][j] - r.position_rad[lo][j]) / span;
      r.velocity_rad_s[k][j] = v;
      r.max_speed_rad_s[j] = std::fmax(r.max_speed_rad_s[j], std::fabs(v));
    }
  }
  r.within_velocity_limits = true;
  for (std::size_t j = 0; j < kNumJoints; ++j) {
    if (r.max_speed_rad_s[j] > model.velocity_limits_rad_s()[j]) r.within_velocity_limits = false;
  }
  r.status = PathStatus::Ok;
  return r;
}

}  // namespace fuzzypid::robot
