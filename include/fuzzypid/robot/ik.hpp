// One entry point to every inverse-kinematics solver of the robot part, for the command-line tool,
// the path planner and the benchmarks.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "fuzzypid/enum_names.hpp"
#include "fuzzypid/robot/analytic_ik.hpp"
#include "fuzzypid/robot/ik_status.hpp"
#include "fuzzypid/robot/kdl_ik.hpp"
#include "fuzzypid/robot/types.hpp"

namespace fuzzypid::robot {

class RobotModel;

enum class IkSolver : std::uint8_t {
  Analytic,  // closed form (AnalyticIk), allocation-free
  KdlNr,     // KDL ChainIkSolverPos_NR_JL
  KdlLma,    // KDL ChainIkSolverPos_LMA with orientation-weighted error
};

// The names of IkSolver (the command-line spelling); to_string and ik_solver_from_string use them.
inline constexpr std::array<EnumName<IkSolver>, 3> kIkSolverNames = {{
    {IkSolver::Analytic, "analytic"},
    {IkSolver::KdlNr, "kdl-nr"},
    {IkSolver::KdlLma, "kdl-lma"},
}};

[[nodiscard]] constexpr const char* to_string(IkSolver s) noexcept {
  return name_of(kIkSolverNames, s);
}

[[nodiscard]] std::optional<IkSolver> ik_solver_from_string(std::string_view name) noexcept;

// Validates a target pose: finite entries and a proper rotation (RᵀR = I and det R = +1 to 1e-6).
[[nodiscard]] bool is_valid_pose(const Pose& pose) noexcept;

class InverseKinematics {
 public:
  // The closed form is available only when the model is the Table 1 geometry (see
  // AnalyticIk::from_model); the KDL solvers always are.
  explicit InverseKinematics(const RobotModel& model, const KdlIkOptions& kdl_options = {});

  bool has_analytic() const noexcept { return analytic_.has_value(); }
  const std::optional<AnalyticIk>& analytic() const noexcept { return analytic_; }
  const KdlIk& kdl() const noexcept { return kdl_; }

  // Rejects invalid poses and seeds with InvalidInput; Analytic without a closed form likewise.
  // `out` is written only when the status is Ok or Singular.
  [[nodiscard]] IkStatus solve(IkSolver solver, const Pose& target, const JointVector& seed,
                               JointVector& out) const noexcept;

 private:
  std::optional<AnalyticIk> analytic_;
  KdlIk kdl_;
};

}  // namespace fuzzypid::robot
