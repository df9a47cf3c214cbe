// KDL's numerical IK solvers behind the KdlIk interface, with results verified by FK.
#include "fuzzypid/robot/kdl_ik.hpp"

#include <cmath>

#include <Eigen/Geometry>
#include <kdl/chainiksolverpos_lma.hpp>
#include <kdl/chainiksolverpos_nr_jl.hpp>
#include <kdl/chainiksolvervel_pinv.hpp>

#include "fuzzypid/robot/ik.hpp"
#include "robot_model_impl.hpp"

namespace fuzzypid::robot {
namespace {

constexpr double kTwoPi = 6.28318530717958647692;

Eigen::Matrix<double, 6, 1> weights(const KdlIkOptions& o) {
  Eigen::Matrix<double, 6, 1> w;
  for (int i = 0; i < 6; ++i)
    w(i) = o.lma_weights[static_cast<std::size_t>(i)];
  return w;
}

KDL::JntArray to_kdl_array(const JointVector& v) {
  KDL::JntArray a(kNumJoints);
  to_kdl(v, a);
  return a;
}

}  // namespace

// Solvers keep references to chain and to fk/vel: members are declared in dependency order and an
// Impl is never moved (KdlIk holds it by unique_ptr).
class KdlIk::Impl {
 public:
  Impl(const KDL::Chain& chain_in, const JointVector& lower_in, const JointVector& upper_in,
       const KdlIkOptions& options_in)
      : chain(chain_in),
        options(options_in),
        lower(lower_in),
        upper(upper_in),
        q_min(to_kdl_array(lower_in)),
        q_max(to_kdl_array(upper_in)),
        fk(chain),
        vel(chain),
        // KDL's NR_JL compares each twist component with eps; a tenth of the tolerance keeps the
        // FK re-check below from rejecting converged results.
        nr(chain, q_min, q_max, fk, vel, options_in.max_iterations, 0.1 * options_in.tolerance),
        lma(chain, weights(options_in), 0.1 * options_in.tolerance,
            static_cast<int>(options_in.max_iterations)),
        q_init(kNumJoints),
        q_out(kNumJoints) {}
  Impl(const Impl& o) : Impl(o.chain, o.lower, o.upper, o.options) {}
  Impl& operator=(const Impl&) = delete;

  KDL::Chain chain;
  KdlIkOptions options;
  JointVector lower;
  JointVector upper;
  KDL::JntArray q_min;
  KDL::JntArray q_max;
  KDL::ChainFkSolverPos_recursive fk;
  KDL::ChainIkSolverVel_pinv vel;
  KDL::ChainIkSolverPos_NR_JL nr;
  KDL::ChainIkSolverPos_LMA lma;
  mutable KDL::JntArray q_init;
  mutable KDL::JntArray q_out;
};

KdlIk::KdlIk(const RobotModel& model, const KdlIkOptions& options)
    : impl_(std::make_unique<Impl>(model.impl().desc.chain, model.lower_limits_rad(),
                                   model.upper_limits_rad(), options)) {}
KdlIk::KdlIk(const KdlIk& other) : impl_(std::make_unique<Impl>(*other.impl_)) {}
KdlIk::KdlIk(KdlIk&& other) noexcept = default;
KdlIk& KdlIk::operator=(const KdlIk& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}
KdlIk& KdlIk::operator=(KdlIk&& other) noexcept = default;
KdlIk::~KdlIk() = default;

const KdlIkOptions& KdlIk::options() const noexcept {
  return impl_->options;
}

IkStatus KdlIk::solve(KdlIkMethod method, const Pose& target, const JointVector& seed,
                      JointVector& out) const noexcept {
  for (double s : seed) {
    if (!std::isfinite(s)) return IkStatus::InvalidInput;
  }
  if (!is_valid_pose(target)) return IkStatus::InvalidInput;
  Impl& im = *impl_;
  try {
    const KDL::Frame goal = to_kdl(target);
    to_kdl(seed, im.q_init);
    if (method == KdlIkMethod::NewtonRaphson) {
      im.nr.CartToJnt(im.q_init, goal, im.q_out);
    } else {
      im.lma.CartToJnt(im.q_init, goal, im.q_out);
    }
    JointVector q = from_kdl(im.q_out);
    // LMA ignores limits: shift each angle by 2 pi towards the seed, then into the limits if
    // that helps, and reject what still lies outside.
    bool within = true;
    for (std::size_t j = 0; j < kNumJoints; ++j) {
      if (!std::isfinite(q[j])) return IkStatus::NoConvergence;
      q[j] += kTwoPi * std::round((seed[j] - q[j]) / kTwoPi);
      if (q[j] < im.lower[j]) q[j] += kTwoPi;
      if (q[j] > im.upper[j]) q[j] -= kTwoPi;
      within = within && q[j] >= im.lower[j] && q[j] <= im.upper[j];
    }
    // The solvers' own return codes are not trusted: the pose reached is.
    KDL::Frame reached;
    to_kdl(q, im.q_out);
    im.fk.JntToCart(im.q_out, reached);
    const Pose p = from_kdl(reached);
    const double position_error = (p.position_m - target.position_m).norm();
    const double rotation_error =
        Eigen::AngleAxisd(p.rotation.transpose() * target.rotation).angle();
    if (!(position_error <= im.options.tolerance && rotation_error <= im.options.tolerance)) {
      return IkStatus::NoConvergence;
    }
    if (!within) return IkStatus::JointLimits;
    out = q;
    return IkStatus::Ok;
  } catch (...) {
    return IkStatus::NoConvergence;
  }
}

}  // namespace fuzzypid::robot
