// RigidBodyDynamics: the algorithms are those of Featherstone, "Rigid Body Dynamics Algorithms"
// (2008), RNEA (Table 5.1) and CRBA (Table 6.2), written with 3-vectors in body coordinates instead
// of 6×6 spatial matrices. A spatial motion is (ω, v) with v the velocity of the body frame's
// origin; a spatial force is (n, f) with n the moment about that origin.
#include "rigid_body_dynamics.hpp"

#include <cmath>

#include <Eigen/Geometry>
#include <kdl/chain.hpp>

namespace fuzzypid::robot::detail {
namespace {

using Vec3 = RigidBodyDynamics::Vec3;
using Mat3 = RigidBodyDynamics::Mat3;
using Vec6 = RigidBodyDynamics::Vec6;
using Mat6 = RigidBodyDynamics::Mat6;

Vec3 to_eigen(const KDL::Vector& v) {
  return Vec3(v.x(), v.y(), v.z());
}

Mat3 to_eigen(const KDL::Rotation& r) {
  Mat3 m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      m(i, j) = r(i, j);
  return m;
}

// The pose of body i in its parent at joint angle q: x_parent = rotation · x_body + position.
struct Placement {
  Mat3 rotation;
  Vec3 position;
};

// The body turns about its own z axis: rotation = R0 · Rz(q), position = p0.
Placement place(const RigidBodyDynamics::Body& b, double q) noexcept {
  const double s = std::sin(q);
  const double c = std::cos(q);
  Placement x;
  x.rotation.col(0) = c * b.rotation0.col(0) + s * b.rotation0.col(1);
  x.rotation.col(1) = c * b.rotation0.col(1) - s * b.rotation0.col(0);
  x.rotation.col(2) = b.rotation0.col(2);
  x.position = b.position0;
  return x;
}

// ẑ × u for u scaled by `rate`: the cross product with a joint rate about z.
Vec3 z_cross(double rate, const Vec3& u) noexcept {
  return Vec3(-rate * u.y(), rate * u.x(), 0.0);
}

// A composite rigid body: mass, first moment and rotational inertia about the frame origin.
struct Inertia {
  double mass;
  Vec3 first_moment;
  Mat3 rotational;
};

// The inertia of a body expressed in its parent's frame (Featherstone Eq. 2.66 in 3-vector form):
// I_parent = E I E^T − m [r]×[r]× − [r]×[h']× − [h']×[r]×, h' = E h, with [a]×[b]× = b aᵀ −
// (a·b) 1.
void add_to_parent(const Inertia& child, const Placement& x, Inertia& parent) noexcept {
  const Vec3& r = x.position;
  const Vec3 h = x.rotation * child.first_moment;
  parent.mass += child.mass;
  parent.first_moment += h + child.mass * r;
  Mat3 shift = child.mass * (r.squaredNorm() * Mat3::Identity() - r * r.transpose());
  shift += 2.0 * r.dot(h) * Mat3::Identity() - h * r.transpose() - r * h.transpose();
  parent.rotational += x.rotation * child.rotational * x.rotation.transpose() + shift;
}

// One recursive Newton-Euler pass with q̈ = 0 (bias = C q̇ + g, gravity entering as a base
// acceleration of +g ẑ) and, with WithMass, the composite-rigid-body algorithm over the same
// placements for M.
template <bool WithMass>
void evaluate(const std::array<RigidBodyDynamics::Body, kNumJoints>& bodies, const Vec6& q,
              const Vec6& qd, double gravity_m_s2, Mat6* mass, Vec6& bias) noexcept {
  std::array<Placement, kNumJoints> x;
  std::array<Vec3, kNumJoints> n;
  std::array<Vec3, kNumJoints> f;

  Vec3 w = Vec3::Zero();
  Vec3 v = Vec3::Zero();
  Vec3 dw = Vec3::Zero();
  Vec3 dv(0.0, 0.0, gravity_m_s2);
  for (std::size_t i = 0; i < kNumJoints; ++i) {
    const RigidBodyDynamics::Body& b = bodies[i];
    x[i] = place(b, q[static_cast<int>(i)]);
    const Mat3 et = x[i].rotation.transpose();
    const double rate = qd[static_cast<int>(i)];
    // The joint's motion subspace is S = (ẑ, 0): the axis is the body's z axis.
    v = et * (v + w.cross(x[i].position));
    w = et * w;
    w.z() += rate;
    dv = et * (dv + dw.cross(x[i].position));
    dw = et * dw;
    // a = X a_parent + v ×m (S q̇), with w × (ẑ q̇) = −(ẑ q̇) × w
    dw -= z_cross(rate, w);
    dv -= z_cross(rate, v);
    // f = I a + v ×f (I v)
    const Vec3 iv_n = b.rotational_inertia * w + b.first_moment.cross(v);
    const Vec3 iv_f = b.mass * v + w.cross(b.first_moment);
    n[i] = b.rotational_inertia * dw + b.first_moment.cross(dv) + w.cross(iv_n) + v.cross(iv_f);
    f[i] = b.mass * dv + dw.cross(b.first_moment) + w.cross(iv_f);
  }

  std::array<Inertia, kNumJoints> composite;
  if constexpr (WithMass) {
    for (std::size_t i = 0; i < kNumJoints; ++i)
      composite[i] = {bodies[i].mass, bodies[i].first_moment, bodies[i].rotational_inertia};
  }
  for (std::size_t k = kNumJoints; k-- > 0;) {
    const int i = static_cast<int>(k);
    bias[i] = n[k].z();
    if (k > 0) {
      const Vec3 fp = x[k].rotation * f[k];
      n[k - 1] += x[k].rotation * n[k] + x[k].position.cross(fp);
      f[k - 1] += fp;
    }
    if constexpr (WithMass) {
      // Column k of M: the composite body's force for a unit joint rate, carried to the root.
      const Inertia& c = composite[k];
      Vec3 cn = c.rotational.col(2);
      Vec3 cf = z_cross(1.0, c.first_moment);
      (*mass)(i, i) = cn.z();
      for (std::size_t j = k; j-- > 0;) {
        const Placement& xj = x[j + 1];
        cf = xj.rotation * cf;
        cn = xj.rotation * cn + xj.position.cross(cf);
        const double m = cn.z();
        (*mass)(i, static_cast<int>(j)) = m;
        (*mass)(static_cast<int>(j), i) = m;
      }
      if (k > 0) add_to_parent(c, x[k], composite[k - 1]);
    }
  }
}

}  // namespace

RigidBodyDynamics::RigidBodyDynamics(const KDL::Chain& chain) {
  // `pending`: the fixed segments since the last moving joint (or since the root), as one frame in
  // that body's tip frame. Their inertia joins the body; their pose starts the next body's
  // placement.
  KDL::Frame pending = KDL::Frame::Identity();
  KDL::RigidBodyInertia merged = KDL::RigidBodyInertia::Zero();
  // turn: the body frame in the segment's tip frame (x_tip = turn · x_body), chosen so that the
  // joint axis is the body's z axis.
  Mat3 turn = Mat3::Identity();
  int body = -1;
  const auto store_inertia = [&] {
    if (body < 0) return;
    Body& b = bodies_[static_cast<std::size_t>(body)];
    b.mass = merged.getMass();
    b.first_moment = turn.transpose() * (b.mass * to_eigen(merged.getCOG()));
    const Mat3 rotational = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(
        merged.getRotationalInertia().data);
    b.rotational_inertia = turn.transpose() * rotational * turn;
  };
  for (const KDL::Segment& segment : chain.segments) {
    const KDL::Frame tip = segment.getFrameToTip();
    if (segment.getJoint().getType() == KDL::Joint::None) {
      pending = pending * tip;
      if (body >= 0) merged = merged + pending * segment.getInertia();
      continue;
    }
    store_inertia();
    if (++body >= static_cast<int>(kNumJoints)) break;
    // Segment pose: Rot(axis, q) · tip in the segment's start frame, the axis passing through the
    // tip frame's origin; in the tip frame the same turn is about a = tip⁻¹ axis, and in the body
    // frame (x_tip = turn · x_body, turn ẑ = a) about ẑ.
    Body& b = bodies_[static_cast<std::size_t>(body)];
    const Vec3 axis = to_eigen(tip.M.Inverse(segment.getJoint().JointAxis())).normalized();
    const Mat3 parent_turn = turn;
    turn = axis == Vec3::UnitZ()
               ? Mat3::Identity()
               : Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), axis).toRotationMatrix();
    const KDL::Frame zero = pending * tip;
    b.rotation0 = parent_turn.transpose() * to_eigen(zero.M) * turn;
    b.position0 = parent_turn.transpose() * to_eigen(zero.p);
    merged = segment.getInertia();
    pending = KDL::Frame::Identity();
  }
  store_inertia();
}

void RigidBodyDynamics::mass_and_bias(const Vec6& q, const Vec6& qd, double gravity_m_s2,
                                      Mat6& mass, Vec6& bias) const noexcept {
  evaluate<true>(bodies_, q, qd, gravity_m_s2, &mass, bias);
}

RigidBodyDynamics::Vec6 RigidBodyDynamics::bias(const Vec6& q, const Vec6& qd,
                                                double gravity_m_s2) const noexcept {
  Vec6 tau;
  evaluate<false>(bodies_, q, qd, gravity_m_s2, nullptr, tau);
  return tau;
}

RigidBodyDynamics::Mat6 RigidBodyDynamics::mass_matrix(const Vec6& q) const noexcept {
  Mat6 m;
  Vec6 unused;
  mass_and_bias(q, Vec6::Zero(), 0.0, m, unused);
  return m;
}

}  // namespace fuzzypid::robot::detail
