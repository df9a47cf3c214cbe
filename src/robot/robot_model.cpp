// RobotModel's queries (forward kinematics, Jacobian, joint-space dynamics) on the KDL chain
// urdf_loader.cpp built, its copies and its payload variant.
#include "robot_model_impl.hpp"

#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

namespace fuzzypid::robot {

namespace {
// Ids of the models made so far: a RobotData names its model by id, not by address (a model
// assigned to gets a new Impl, which may reuse a freed address).
std::atomic<std::uint64_t> g_next_model_id{1};
}  // namespace

RobotModel::Impl::Impl(ChainDescription description)
    : desc(std::move(description)),
      dynamics(desc.chain),
      id(g_next_model_id.fetch_add(1, std::memory_order_relaxed)) {}

RobotData::Impl::Impl(const RobotModel::Impl& model)
    : model_id(model.id),
      chain(model.desc.chain),
      fk_solver(chain),
      jac_solver(chain),
      dyn_solver(chain, KDL::Vector(0.0, 0.0, -1.0)),
      q(kNumJoints),
      qd(kNumJoints),
      tau(kNumJoints),
      jac(kNumJoints),
      mass(kNumJoints) {}

RobotData::RobotData(const RobotModel& model) : impl_(std::make_unique<Impl>(model.impl())) {}
RobotData::RobotData(RobotData&& other) noexcept = default;
RobotData& RobotData::operator=(RobotData&& other) noexcept = default;
RobotData::~RobotData() = default;

RobotModel::RobotModel(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
RobotModel::RobotModel(const RobotModel& other) : impl_(std::make_unique<Impl>(*other.impl_)) {}
RobotModel::RobotModel(RobotModel&& other) noexcept = default;
RobotModel& RobotModel::operator=(const RobotModel& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}
RobotModel& RobotModel::operator=(RobotModel&& other) noexcept = default;
RobotModel::~RobotModel() = default;

RobotModel RobotModel::with_payload(double mass_kg) const {
  ChainDescription desc = impl_->desc;
  if (mass_kg > 0.0) {
    // The last segment's inertia is expressed in its tip frame: a point mass at that frame's
    // origin has no first moment and no rotational inertia about it.
    KDL::Segment& last = desc.chain.segments.back();
    last.setInertia(last.getInertia() + KDL::RigidBodyInertia(mass_kg));
  }
  return RobotModel(std::make_unique<Impl>(std::move(desc)));
}

const std::string& RobotModel::robot_name() const noexcept {
  return impl_->desc.robot_name;
}
bool RobotModel::continuous(std::size_t joint) const noexcept {
  return joint < kNumJoints && impl_->desc.continuous[joint];
}
const std::string& RobotModel::root_link() const noexcept {
  return impl_->desc.root_link;
}
const std::string& RobotModel::tip_link() const noexcept {
  return impl_->desc.tip_link;
}
const std::array<std::string, kNumJoints>& RobotModel::joint_names() const noexcept {
  return impl_->desc.joint_names;
}
const JointVector& RobotModel::lower_limits_rad() const noexcept {
  return impl_->desc.lower;
}
const JointVector& RobotModel::upper_limits_rad() const noexcept {
  return impl_->desc.upper;
}
const JointVector& RobotModel::velocity_limits_rad_s() const noexcept {
  return impl_->desc.velocity;
}
const JointVector& RobotModel::effort_limits_nm() const noexcept {
  return impl_->desc.effort;
}
double RobotModel::moving_mass_kg() const noexcept {
  return impl_->desc.moving_mass_kg;
}
const std::vector<std::string>& RobotModel::notes() const noexcept {
  return impl_->desc.notes;
}

bool RobotModel::within_limits(const JointVector& q, double tolerance_rad) const noexcept {
  for (std::size_t i = 0; i < kNumJoints; ++i) {
    if (!(q[i] >= impl_->desc.lower[i] - tolerance_rad &&
          q[i] <= impl_->desc.upper[i] + tolerance_rad))
      return false;
  }
  return true;
}

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr JointVector kNaNJoints = {kNaN, kNaN, kNaN, kNaN, kNaN, kNaN};
}  // namespace

Pose RobotModel::forward_kinematics(const JointVector& q, RobotData& data) const noexcept {
  RobotData::Impl& d = data.impl();
  if (d.model_id != impl_->id) {
    Pose p;
    p.position_m.setConstant(kNaN);
    p.rotation.setConstant(kNaN);
    return p;
  }
  to_kdl(q, d.q);
  KDL::Frame f;
  d.fk_solver.JntToCart(d.q, f);
  return from_kdl(f);
}

Eigen::Matrix<double, 6, 6> RobotModel::jacobian(const JointVector& q,
                                                 RobotData& data) const noexcept {
  RobotData::Impl& d = data.impl();
  if (d.model_id != impl_->id) return Eigen::Matrix<double, 6, 6>::Constant(kNaN);
  to_kdl(q, d.q);
  d.jac_solver.JntToJac(d.q, d.jac);
  return d.jac.data;
}

Eigen::Matrix<double, 6, 6> RobotModel::mass_matrix(const JointVector& q,
                                                    RobotData& data) const noexcept {
  RobotData::Impl& d = data.impl();
  if (d.model_id != impl_->id) return Eigen::Matrix<double, 6, 6>::Constant(kNaN);
  to_kdl(q, d.q);
  d.dyn_solver.JntToMass(d.q, d.mass);
  return d.mass.data;
}

JointVector RobotModel::inertia_diagonal(const JointVector& q, RobotData& data) const noexcept {
  RobotData::Impl& d = data.impl();
  if (d.model_id != impl_->id) return kNaNJoints;
  JointVector out{};
  to_kdl(q, d.q);
  d.dyn_solver.JntToMass(d.q, d.mass);
  for (std::size_t i = 0; i < kNumJoints; ++i) {
    const auto k = static_cast<unsigned int>(i);
    out[i] = d.mass(k, k);
  }
  return out;
}

JointVector RobotModel::coriolis_torque(const JointVector& q, const JointVector& qd,
                                        RobotData& data) const noexcept {
  RobotData::Impl& d = data.impl();
  if (d.model_id != impl_->id) return kNaNJoints;
  to_kdl(q, d.q);
  to_kdl(qd, d.qd);
  d.dyn_solver.JntToCoriolis(d.q, d.qd, d.tau);
  return from_kdl(d.tau);
}

// The fixed-size RNEA with q̇ = 0 (about a third of KDL's JntToGravity here, docs/performance.md):
// gravity feed-forward evaluates it every tick.
JointVector RobotModel::gravity_torque(const JointVector& q, double gravity_m_s2) const noexcept {
  const detail::RigidBodyDynamics::Vec6 g =
      impl_->dynamics.bias(Eigen::Map<const detail::RigidBodyDynamics::Vec6>(q.data()),
                           detail::RigidBodyDynamics::Vec6::Zero(), gravity_m_s2);
  JointVector out{};
  Eigen::Map<detail::RigidBodyDynamics::Vec6>(out.data()) = g;
  return out;
}

namespace detail {
const RigidBodyDynamics& dynamics_of(const RobotModel& model) noexcept {
  return model.impl().dynamics;
}

JointVector kdl_gravity_torque(const RobotModel& model, const JointVector& q, double gravity_m_s2,
                               RobotData& data) noexcept {
  RobotData::Impl& d = data.impl();
  if (d.model_id != model.impl().id) return kNaNJoints;
  to_kdl(q, d.q);
  d.dyn_solver.JntToGravity(d.q, d.tau);
  JointVector g = from_kdl(d.tau);
  for (double& v : g)
    v *= gravity_m_s2;
  return g;
}
}  // namespace detail

}  // namespace fuzzypid::robot
