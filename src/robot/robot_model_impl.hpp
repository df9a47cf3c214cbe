// Internal: the KDL state behind RobotModel. Included only by src/robot/*.cpp.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <kdl/chain.hpp>
#include <kdl/chaindynparam.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainjnttojacsolver.hpp>
#include <kdl/jacobian.hpp>
#include <kdl/jntarray.hpp>
#include <kdl/jntspaceinertiamatrix.hpp>

#include "fuzzypid/robot/robot_data.hpp"
#include "fuzzypid/robot/robot_model.hpp"
#include "rigid_body_dynamics.hpp"

namespace fuzzypid::robot {

struct ChainDescription {
  KDL::Chain chain;
  std::string robot_name;  // the URDF's <robot name=...>
  std::string root_link;
  std::string tip_link;
  std::array<std::string, kNumJoints> joint_names;
  JointVector lower{};
  JointVector upper{};
  JointVector velocity{};
  JointVector effort{};
  std::array<bool, kNumJoints> continuous{};  // URDF continuous joints (no position limits)
  double moving_mass_kg = 0.0;                // the links below the first joint, payload aside
  std::vector<std::string> notes;             // RobotModel::notes()
};

// Owns the chain, which no query of the model solves on (a RobotData solves on its own copy), and
// the fixed-size dynamics built from it. Every Impl has its own id (a copy too), so a RobotData
// can tell the model it was made for.
class RobotModel::Impl {
 public:
  explicit Impl(ChainDescription description);
  Impl(const Impl& other) : Impl(other.desc) {}
  Impl& operator=(const Impl&) = delete;

  ChainDescription desc;
  // The same chain's parameters for the fixed-size dynamics (coupled plant, gravity_torque).
  detail::RigidBodyDynamics dynamics;
  std::uint64_t id;
};

// A copy of one model's chain, the solvers bound to it and their scratch (sized at construction,
// never reallocated). The copy is needed: KDL's solvers change their own state when they solve,
// and so does the chain itself (each KDL::Joint caches the rotation of its last angle in mutable
// members), so two threads solving on one chain race (RobotModel.TwoThreadsQueryOneModel...).
class RobotData::Impl {
 public:
  explicit Impl(const RobotModel::Impl& model);
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  std::uint64_t model_id;
  KDL::Chain chain;  // the solvers below keep a reference to it: an Impl is never moved
  KDL::ChainFkSolverPos_recursive fk_solver;
  KDL::ChainJntToJacSolver jac_solver;
  KDL::ChainDynParam dyn_solver;  // built with unit gravity along -z (results scale linearly)
  KDL::JntArray q;
  KDL::JntArray qd;
  KDL::JntArray tau;
  KDL::Jacobian jac;
  KDL::JntSpaceInertiaMatrix mass;
};

// Copies a joint vector into a preallocated KDL array of the same size.
inline void to_kdl(const JointVector& v, KDL::JntArray& out) noexcept {
  for (std::size_t i = 0; i < kNumJoints; ++i)
    out(static_cast<unsigned int>(i)) = v[i];
}

inline JointVector from_kdl(const KDL::JntArray& a) noexcept {
  JointVector v{};
  for (std::size_t i = 0; i < kNumJoints; ++i)
    v[i] = a(static_cast<unsigned int>(i));
  return v;
}

inline Pose from_kdl(const KDL::Frame& f) noexcept {
  Pose p;
  p.position_m = Eigen::Vector3d(f.p.x(), f.p.y(), f.p.z());
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      p.rotation(r, c) = f.M(r, c);
  return p;
}

inline KDL::Frame to_kdl(const Pose& p) noexcept {
  const Eigen::Matrix3d& R = p.rotation;
  return KDL::Frame(KDL::Rotation(R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0),
                                  R(2, 1), R(2, 2)),
                    KDL::Vector(p.position_m.x(), p.position_m.y(), p.position_m.z()));
}

}  // namespace fuzzypid::robot
