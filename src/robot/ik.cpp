// The InverseKinematics facade and pose validation.
#include "fuzzypid/robot/ik.hpp"

#include <cmath>

#include <Eigen/LU>

#include "fuzzypid/robot/robot_model.hpp"

namespace fuzzypid::robot {

std::optional<IkSolver> ik_solver_from_string(std::string_view name) noexcept {
  return parse_enum(kIkSolverNames, name);
}

bool is_valid_pose(const Pose& pose) noexcept {
  if (!pose.position_m.allFinite() || !pose.rotation.allFinite()) return false;
  const Eigen::Matrix3d e = pose.rotation.transpose() * pose.rotation - Eigen::Matrix3d::Identity();
  return e.cwiseAbs().maxCoeff() <= 1e-6 && pose.rotation.determinant() > 0.0;
}

InverseKinematics::InverseKinematics(const RobotModel& model, const KdlIkOptions& kdl_options)
    : analytic_(AnalyticIk::from_model(model)), kdl_(model, kdl_options) {}

IkStatus InverseKinematics::solve(IkSolver solver, const Pose& target, const JointVector& seed,
                                  JointVector& out) const noexcept {
  switch (solver) {
    case IkSolver::Analytic:
      if (!analytic_) return IkStatus::InvalidInput;
      return analytic_->solve(target, seed, out);
    case IkSolver::KdlNr:
      return kdl_.solve(KdlIkMethod::NewtonRaphson, target, seed, out);
    case IkSolver::KdlLma:
      return kdl_.solve(KdlIkMethod::LevenbergMarquardt, target, seed, out);
  }
  return IkStatus::InvalidInput;
}

}  // namespace fuzzypid::robot
