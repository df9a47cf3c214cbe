// The kinematic and dynamic model of a six-joint serial arm, loaded from a URDF through urdfdom and
// evaluated with Orocos KDL. No KDL or urdfdom type appears here: the KDL chain lives behind a
// pointer to an implementation, the solvers and their scratch in a RobotData (robot_data.hpp).
//
// Thread safety: a RobotModel is immutable once loaded; any number of threads may query one model
// at once, each with its own RobotData.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fuzzypid/robot/robot_data.hpp"
#include "fuzzypid/robot/types.hpp"

namespace fuzzypid::robot {

struct LoadResult;

// The bundled ER50-C20 URDF: $FUZZYPID_URDF if set and non-empty, else the source tree's
// urdf/er50_c20.urdf if it exists, else the installed <datadir>/fuzzypid/urdf/er50_c20.urdf.
[[nodiscard]] std::string default_urdf_path();

// The bundled ER50-C20's reflected motor inertia (rotor inertia x gear ratio²), kg·m²: estimates
// from catalogue rotor inertias of 50 kg-class arms (docs/robot.md), each uncertain by a factor of
// two. A URDF has no armature field; this is the bundled robot's, no other's.
inline constexpr JointVector kEr50ArmatureKgm2 = {8.5, 16.0, 5.4, 1.7, 1.7, 0.5};

class RobotModel {
 public:
  // Parses urdf_path and extracts the chain root_link -> tip_link. An empty root_link means the
  // URDF's root link; an empty tip_link means the end of the unique path of links below the root
  // (an error if the tree branches). The chain must have exactly kNumJoints revolute or continuous
  // joints. Never throws: every failure is reported in LoadResult::error.
  [[nodiscard]] static LoadResult load(const std::string& urdf_path,
                                       const std::string& root_link = "",
                                       const std::string& tip_link = "");

  RobotModel(const RobotModel& other);
  RobotModel(RobotModel&& other) noexcept;
  RobotModel& operator=(const RobotModel& other);
  RobotModel& operator=(RobotModel&& other) noexcept;
  ~RobotModel();

  // A copy of this model with a point mass of mass_kg added at the origin of the chain's tip frame
  // (the tool flange): the inertia it adds depends on the configuration, and mass_matrix,
  // inertia_diagonal, coriolis_torque, gravity_torque and the plant's dynamics all include it.
  // Precondition: mass_kg finite and >= 0 (callers validate user input); 0 returns an equal copy.
  [[nodiscard]] RobotModel with_payload(double mass_kg) const;

  // The URDF's <robot name=...> attribute.
  const std::string& robot_name() const noexcept;
  // True when joint (0-based, < kNumJoints) is a URDF continuous joint (infinite position limits);
  // false for a revolute joint or an index out of range.
  bool continuous(std::size_t joint) const noexcept;

  const std::string& root_link() const noexcept;
  const std::string& tip_link() const noexcept;
  const std::array<std::string, kNumJoints>& joint_names() const noexcept;

  // Limits as written in the URDF; a continuous joint has infinite position limits.
  const JointVector& lower_limits_rad() const noexcept;
  const JointVector& upper_limits_rad() const noexcept;
  const JointVector& velocity_limits_rad_s() const noexcept;
  const JointVector& effort_limits_nm() const noexcept;
  bool within_limits(const JointVector& q, double tolerance_rad = 0.0) const noexcept;

  // The mass the joints move: the links of the chain below its first joint, kg (a payload added
  // by with_payload not included).
  double moving_mass_kg() const noexcept;

  // What the URDF leaves open that a user should hear, one line per joint and limit, e.g.
  // "joint 'j1': <limit> effort=\"0\" means no limit: its torque is never clamped". Empty for the
  // bundled ER50-C20.
  const std::vector<std::string>& notes() const noexcept;

  // The queries below work in `data`, a RobotData made for this model (robot_data.hpp), and do
  // not allocate. With a RobotData made for another model every number they return is NaN.

  // Tip pose in the root frame.
  Pose forward_kinematics(const JointVector& q, RobotData& data) const noexcept;

  // Geometric Jacobian: rows 0-2 map q̇ to the linear velocity (m/s) of the tip origin, rows 3-5 to
  // the angular velocity (rad/s), both expressed in the root frame.
  Eigen::Matrix<double, 6, 6> jacobian(const JointVector& q, RobotData& data) const noexcept;

  // Joint-space inertia matrix M(q) (kg·m²) of the links alone (no motor armature).
  Eigen::Matrix<double, 6, 6> mass_matrix(const JointVector& q, RobotData& data) const noexcept;

  // Diagonal of mass_matrix(q): the inertia each joint sees with the others locked.
  JointVector inertia_diagonal(const JointVector& q, RobotData& data) const noexcept;

  // Coriolis and centrifugal torques C(q, q̇)·q̇ (N·m).
  JointVector coriolis_torque(const JointVector& q, const JointVector& qd,
                              RobotData& data) const noexcept;

  // Gravity torques g(q) (N·m) for gravity along -z of the root frame with the given magnitude.
  // A fixed-size recursive Newton-Euler pass (equal to KDL's ChainDynParam within 1e-12 relative,
  // about a third of its cost): cheap enough for a feed-forward every tick. Needs no RobotData;
  // does not allocate.
  JointVector gravity_torque(const JointVector& q, double gravity_m_s2 = 9.81) const noexcept;

  class Impl;  // defined in src/robot/robot_model_impl.hpp; used by the other robot sources
  const Impl& impl() const noexcept { return *impl_; }

 private:
  explicit RobotModel(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

struct LoadResult {
  std::optional<RobotModel> model;  // set on success
  std::string error;                // empty on success, a human-readable reason otherwise
};

}  // namespace fuzzypid::robot
