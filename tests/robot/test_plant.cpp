// The joint plant: RK4 under zero-order hold, inertia from the model, saturation, bad input; the
// fixed-size rigid-body dynamics of the coupled mode against KDL; the point-mass payload.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "fuzzypid/robot/path.hpp"
#include "fuzzypid/robot/plant.hpp"
#include "fuzzypid_support/uniform_real.hpp"
#include "rigid_body_dynamics.hpp"
#include "test_support.hpp"

namespace fuzzypid::robot {
namespace {

using test::bundled_model;
using test::coriolis_of;
using test::inertia_diagonal_of;
using test::jacobian_of;
using test::mass_matrix_of;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

Vec6 to_vec(const JointVector& v) {
  return Eigen::Map<const Vec6>(v.data());
}

// Closed form of J θ̈ = τ − b θ̇ from (θ0, ω0) after t seconds.
void closed_form(double j, double b, double tau, double th0, double w0, double t, double& th,
                 double& w) {
  if (b == 0.0) {
    th = th0 + w0 * t + 0.5 * tau / j * t * t;
    w = w0 + tau / j * t;
    return;
  }
  const double w_inf = tau / b;
  const double e = std::exp(-b * t / j);
  w = w_inf + (w0 - w_inf) * e;
  th = th0 + w_inf * t + (w0 - w_inf) * (j / b) * (1.0 - e);
}

PlantConfig fixed_inertia_config() {
  PlantConfig c;
  c.inertia_update = InertiaUpdate::Fixed;
  c.damping_nms = {40.0, 60.0, 20.0, 2.0, 1.5, 0.5};
  return c;
}

TEST(JointPlant, ConstantTorqueMatchesTheClosedFormOfADampedInertia) {
  JointPlant plant(bundled_model(), fixed_inertia_config());
  ASSERT_TRUE(plant.valid());
  const JointVector q0 = {0.3, -1.2, 0.1, 0.5, -0.4, -1.5};
  const JointVector w0 = {0.1, -0.2, 0.0, 0.3, 0.0, -0.1};
  plant.reset(q0, w0);
  const JointVector j = plant.inertia();
  const JointVector tau = {100.0, -200.0, 50.0, 5.0, -3.0, 1.0};
  for (int tick = 0; tick < 100; ++tick)
    ASSERT_EQ(plant.step(tau, 0.05), PlantStatus::Ok);
  for (std::size_t i = 0; i < kNumJoints; ++i) {
    double th = 0.0;
    double w = 0.0;
    closed_form(j[i], plant.config().damping_nms[i], tau[i], q0[i], w0[i], 5.0, th, w);
    EXPECT_NEAR(plant.position()[i], th, 1e-9) << "joint " << i + 1;
    EXPECT_NEAR(plant.velocity()[i], w, 1e-9) << "joint " << i + 1;
  }
  EXPECT_NEAR(plant.time_s(), 5.0, 1e-12);
}

TEST(JointPlant, TickThatIsNotAMultipleOfTheSubstepEndsExactly) {
  PlantConfig c = fixed_inertia_config();
  c.substep_s = 1e-3;
  JointPlant plant(bundled_model(), c);
  plant.reset(JointVector{}, JointVector{});
  const JointVector tau = {10.0, 10.0, 10.0, 1.0, 1.0, 1.0};
  const double dt = 0.0123;  // 12 full substeps and one of 0.3 ms
  for (int tick = 0; tick < 50; ++tick)
    ASSERT_EQ(plant.step(tau, dt), PlantStatus::Ok);
  for (std::size_t i = 0; i < kNumJoints; ++i) {
    double th = 0.0;
    double w = 0.0;
    closed_form(plant.inertia()[i], c.damping_nms[i], tau[i], 0.0, 0.0, 50 * dt, th, w);
    EXPECT_NEAR(plant.position()[i], th, 1e-9);
    EXPECT_NEAR(plant.velocity()[i], w, 1e-9);
  }
}

TEST(JointPlant, UndampedJointIsAnExactDoubleIntegrator) {
  PlantConfig c;
  c.inertia_update = InertiaUpdate::Fixed;
  JointPlant plant(bundled_model(), c);
  plant.reset(JointVector{}, JointVector{});
  const JointVector tau = {1.0, 2.0, 3.0, 0.4, 0.5, 0.6};
  ASSERT_EQ(plant.step(tau, 1.0), PlantStatus::Ok);
  for (std::size_t i = 0; i < kNumJoints; ++i) {
    EXPECT_NEAR(plant.position()[i], 0.5 * tau[i] / plant.inertia()[i], 1e-12);
    EXPECT_NEAR(plant.acceleration()[i], tau[i] / plant.inertia()[i], 1e-12);
  }
}

TEST(JointPlant, InertiaIsTheModelDiagonalPlusArmatureAtTheStartOfEachTick) {
  PlantConfig c;
  c.inertia_scale = {1.0, 2.0, 1.0, 1.0, 1.0, 1.0};
  JointPlant plant(bundled_model(), c);
  const JointVector q0 = {0.3, -1.2, 0.1, 0.5, -0.4, -1.5};
  plant.reset(q0, JointVector{});
  const JointVector tau = {500.0, 500.0, 200.0, 10.0, 10.0, 5.0};
  ASSERT_EQ(plant.step(tau, 0.05), PlantStatus::Ok);
  const JointVector d0 = inertia_diagonal_of(bundled_model(), q0);
  for (std::size_t i = 0; i < kNumJoints; ++i) {
    EXPECT_DOUBLE_EQ(plant.inertia()[i], c.inertia_scale[i] * d0[i] + c.armature_kgm2[i]);
  }
  const JointVector q1 = plant.position();
  ASSERT_EQ(plant.step(tau, 0.05), PlantStatus::Ok);
  const JointVector d1 = inertia_diagonal_of(bundled_model(), q1);
  EXPECT_DOUBLE_EQ(plant.inertia()[0], d1[0] + c.armature_kgm2[0]);
  EXPECT_NE(plant.inertia()[0], d0[0] + c.armature_kgm2[0]);  // J1 depends on the arm's reach
}

TEST(JointPlant, TorqueBeyondTheEffortLimitSaturates) {
  JointPlant plant(bundled_model());
  plant.reset(JointVector{}, JointVector{});
  const JointVector tau = {1e6, 0.0, 0.0, 0.0, -1e6, 0.0};
  EXPECT_EQ(plant.step(tau, 0.05), PlantStatus::Saturated);
  EXPECT_EQ(plant.applied_torque()[0], bundled_model().effort_limits_nm()[0]);
  EXPECT_EQ(plant.applied_torque()[4], -bundled_model().effort_limits_nm()[4]);
  EXPECT_TRUE(plant.saturated()[0]);
  EXPECT_FALSE(plant.saturated()[1]);
  EXPECT_TRUE(plant.saturated()[4]);
  EXPECT_EQ(plant.step(JointVector{}, 0.05), PlantStatus::Ok);
  EXPECT_FALSE(plant.saturated()[0]);
}

TEST(JointPlant, NonFiniteTorqueOrBadTickIsRejectedWithoutChangingTheState) {
  JointPlant plant(bundled_model());
  plant.reset({0.1, 0.2, 0.3, 0.4, 0.5, 0.6}, {0.01, 0.0, 0.0, 0.0, 0.0, 0.0});
  ASSERT_EQ(plant.step({1.0, 1.0, 1.0, 1.0, 1.0, 1.0}, 0.05), PlantStatus::Ok);
  const JointVector q = plant.position();
  const JointVector v = plant.velocity();
  const double t = plant.time_s();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(plant.step({nan, 0, 0, 0, 0, 0}, 0.05), PlantStatus::InvalidInput);
  EXPECT_EQ(plant.step({0, 0, inf, 0, 0, 0}, 0.05), PlantStatus::InvalidInput);
  EXPECT_EQ(plant.step(JointVector{}, 0.0), PlantStatus::InvalidInput);
  EXPECT_EQ(plant.step(JointVector{}, -0.05), PlantStatus::InvalidInput);
  EXPECT_EQ(plant.step(JointVector{}, nan), PlantStatus::InvalidInput);
  EXPECT_EQ(plant.step(JointVector{}, 0.05, {0, 0, 0, 0, 0, nan}), PlantStatus::InvalidInput);
  EXPECT_EQ(plant.position(), q);
  EXPECT_EQ(plant.velocity(), v);
  EXPECT_EQ(plant.time_s(), t);
}

TEST(JointPlant, InvalidConfigurationIsReportedAndRefusesToStep) {
  PlantConfig c;
  c.armature_kgm2[2] = -1.0;
  JointPlant plant(bundled_model(), c);
  EXPECT_FALSE(plant.valid());
  EXPECT_EQ(plant.step(JointVector{}, 0.05), PlantStatus::InvalidInput);
  c = PlantConfig{};
  c.substep_s = 0.0;
  EXPECT_FALSE(JointPlant(bundled_model(), c).valid());
  c = PlantConfig{};
  c.coupled_substep_s = 0.0;
  EXPECT_FALSE(JointPlant(bundled_model(), c).valid());
  c = PlantConfig{};
  c.coupled_step_rad = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(JointPlant(bundled_model(), c).valid());
  c.coupled_step_rad = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(JointPlant(bundled_model(), c).valid());
}

TEST(JointPlant, DisturbanceTorqueAddsToTheDrive) {
  PlantConfig c;
  c.inertia_update = InertiaUpdate::Fixed;
  JointPlant a(bundled_model(), c);
  JointPlant b(bundled_model(), c);
  a.reset(JointVector{}, JointVector{});
  b.reset(JointVector{}, JointVector{});
  ASSERT_EQ(a.step({3, 0, 0, 0, 0, 0}, 0.05), PlantStatus::Ok);
  ASSERT_EQ(b.step({1, 0, 0, 0, 0, 0}, 0.05, {2, 0, 0, 0, 0, 0}), PlantStatus::Ok);
  EXPECT_NEAR(a.position()[0], b.position()[0], 1e-15);
}

TEST(JointPlant, CoupledModelConservesKineticEnergyWithoutTorqueOrGravity) {
  PlantConfig c;
  c.coupling = PlantCoupling::Coupled;
  JointPlant plant(bundled_model(), c);
  const JointVector q0 = {0.3, -1.2, 0.1, 0.5, -0.4, -1.5};
  const JointVector w0 = {0.5, -0.4, 0.6, 1.0, -0.8, 1.2};
  plant.reset(q0, w0);
  const auto energy = [&](const JointVector& q, const JointVector& w) {
    Eigen::Matrix<double, 6, 6> m = mass_matrix_of(bundled_model(), q);
    m.diagonal() += Eigen::Map<const Eigen::Matrix<double, 6, 1>>(c.armature_kgm2.data());
    const Eigen::Map<const Eigen::Matrix<double, 6, 1>> v(w.data());
    return 0.5 * v.dot(m * v);
  };
  const double e0 = energy(q0, w0);
  for (int tick = 0; tick < 20; ++tick)
    ASSERT_EQ(plant.step(JointVector{}, 0.05), PlantStatus::Ok);
  const double e1 = energy(plant.position(), plant.velocity());
  EXPECT_NEAR(e1 / e0, 1.0, 1e-7);
  EXPECT_NE(plant.position(), q0);
}

TEST(JointPlant, CoupledModelAtRestStaysAtRestWithGravityOffAndFallsWithItOn) {
  PlantConfig c;
  c.coupling = PlantCoupling::Coupled;
  JointPlant still(bundled_model(), c);
  const JointVector q0 = {0.0, -0.5, 0.3, 0.0, 0.2, 0.0};
  still.reset(q0, JointVector{});
  ASSERT_EQ(still.step(JointVector{}, 0.05), PlantStatus::Ok);
  EXPECT_EQ(still.position(), q0);
  c.gravity = true;
  JointPlant falling(bundled_model(), c);
  falling.reset(q0, JointVector{});
  ASSERT_EQ(falling.step(JointVector{}, 0.05), PlantStatus::Ok);
  EXPECT_GT(std::fabs(falling.position()[1] - q0[1]), 1e-4);
}

TEST(JointPlant, CopiesStepIndependently) {
  JointPlant a(bundled_model());
  a.reset(kPaperStartJoints, JointVector{});
  JointPlant b = a;
  ASSERT_EQ(a.step({10, 0, 0, 0, 0, 0}, 0.05), PlantStatus::Ok);
  EXPECT_EQ(b.position(), kPaperStartJoints);
}

// Uniform in [lo, hi], the same draws on every standard library.
double uniform(std::mt19937_64& rng, double lo, double hi) {
  return fuzzypid::support::UniformReal<double>(lo, hi)(rng);
}

// A six-joint URDF with random joint origins (position and orientation), random unit axes, random
// masses, centers of mass and inertia tensors, a massive fixed link between joints 3 and 4, fixed
// mounts before joint 1 and a tool after joint 6: every path of the parameter extraction.
std::string random_arm_urdf(std::mt19937_64& rng) {
  const auto u = [&rng] { return uniform(rng, -1.0, 1.0); };
  std::ostringstream x;
  x.precision(17);
  const auto origin = [&] {
    std::ostringstream o;
    o.precision(17);
    o << "<origin xyz=\"" << 0.4 * u() << " " << 0.4 * u() << " " << 0.4 * u() << "\" rpy=\""
      << 3.0 * u() << " " << 1.5 * u() << " " << 3.0 * u() << "\"/>";
    return o.str();
  };
  const auto link = [&](const std::string& name) {
    // A positive-definite tensor satisfying the triangle inequality: a box's principal moments,
    // turned by the inertial origin's rpy.
    const double m = uniform(rng, 1.0, 40.0);
    const double a = 0.1 + 0.5 * std::fabs(u());
    const double b = 0.1 + 0.5 * std::fabs(u());
    const double c = 0.1 + 0.5 * std::fabs(u());
    x << "<link name=\"" << name << "\"><inertial>" << origin() << "<mass value=\"" << m
      << "\"/><inertia ixx=\"" << m * (b * b + c * c) / 12 << "\" ixy=\"0\" ixz=\"0\" iyy=\""
      << m * (a * a + c * c) / 12 << "\" iyz=\"0\" izz=\"" << m * (a * a + b * b) / 12
      << "\"/></inertial></link>\n";
  };
  const auto joint = [&](const std::string& name, const std::string& parent,
                         const std::string& child, bool fixed) {
    x << "<joint name=\"" << name << "\" type=\"" << (fixed ? "fixed" : "revolute") << "\">"
      << "<parent link=\"" << parent << "\"/><child link=\"" << child << "\"/>" << origin();
    if (!fixed) {
      Eigen::Vector3d axis;
      for (int k = 0; k < 3; ++k)
        axis[k] = u();
      axis.normalize();
      x << "<axis xyz=\"" << axis.x() << " " << axis.y() << " " << axis.z() << "\"/>"
        << "<limit lower=\"-3\" upper=\"3\" velocity=\"2\" effort=\"1000\"/>";
    }
    x << "</joint>\n";
  };
  x << "<?xml version=\"1.0\"?>\n<robot name=\"random_arm\">\n<link name=\"world\"/>\n";
  link("mount");
  joint("mount_joint", "world", "mount", true);
  const char* names[] = {"l1", "l2", "l3", "l3b", "l4", "l5", "l6", "tool"};
  std::string parent = "mount";
  for (const char* name : names) {
    link(name);
    const bool fixed = std::string(name) == "l3b" || std::string(name) == "tool";
    joint(std::string("j_") + name, parent, name, fixed);
    parent = name;
  }
  x << "</robot>\n";
  return x.str();
}

RobotModel load_text(const std::string& urdf, const std::string& file_name) {
  const std::string path = testing::TempDir() + file_name;
  std::ofstream(path) << urdf;
  LoadResult r = RobotModel::load(path);
  if (!r.model) {
    std::fprintf(stderr, "cannot load %s: %s\n", path.c_str(), r.error.c_str());
    std::abort();
  }
  return std::move(*r.model);
}

// max |a − b| relative to max(1, max |b|).
template <typename A, typename B>
double relative_error(const A& a, const B& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(1.0, b.cwiseAbs().maxCoeff());
}

// M, C q̇ and g of the fixed-size RNEA/CRBA (g also through RobotModel::gravity_torque) equal KDL's
// ChainDynParam (behind RobotModel's mass_matrix and coriolis_torque) to 1e-9 relative, on the
// bundled arm, on it with a payload, and on random arms.
void expect_dynamics_match_kdl(const RobotModel& model, std::mt19937_64& rng, int states) {
  const detail::RigidBodyDynamics& fast = detail::dynamics_of(model);
  RobotData data(model);
  double worst_m = 0.0;
  double worst_c = 0.0;
  double worst_g = 0.0;
  for (int k = 0; k < states; ++k) {
    JointVector q{};
    JointVector qd{};
    for (std::size_t i = 0; i < kNumJoints; ++i) {
      q[i] = uniform(rng, -3.2, 3.2);
      qd[i] = uniform(rng, -3.0, 3.0);
    }
    const double g = 9.81;
    Mat6 m;
    Vec6 bias;
    fast.mass_and_bias(to_vec(q), to_vec(qd), g, m, bias);
    const Vec6 coriolis = to_vec(coriolis_of(model, q, qd));
    const Vec6 gravity = to_vec(detail::kdl_gravity_torque(model, q, g, data));
    worst_g = std::max(worst_g, relative_error(to_vec(model.gravity_torque(q, g)), gravity));
    worst_m = std::max(worst_m, relative_error(m, mass_matrix_of(model, q)));
    worst_m =
        std::max(worst_m, relative_error(fast.mass_matrix(to_vec(q)), mass_matrix_of(model, q)));
    worst_c = std::max(worst_c, relative_error(fast.bias(to_vec(q), to_vec(qd), 0.0), coriolis));
    worst_g = std::max(worst_g, relative_error(fast.bias(to_vec(q), Vec6::Zero(), g), gravity));
    worst_g = std::max(worst_g, relative_error(bias, Vec6(coriolis + gravity)));
  }
  std::printf("[ dynamics ] %s: worst relative error M %.2e, C q̇ %.2e, g %.2e\n",
              model.robot_name().c_str(), worst_m, worst_c, worst_g);
  EXPECT_LT(worst_m, 1e-9);
  EXPECT_LT(worst_c, 1e-9);
  EXPECT_LT(worst_g, 1e-9);
}

TEST(RigidBodyDynamics, MassCoriolisAndGravityEqualKdlOnTheBundledArm) {
  std::mt19937_64 rng = test::seeded_rng(18, "random states");
  expect_dynamics_match_kdl(bundled_model(), rng, 2000);
  expect_dynamics_match_kdl(bundled_model().with_payload(25.0), rng, 2000);
}

TEST(RigidBodyDynamics, MassCoriolisAndGravityEqualKdlOnRandomArms) {
  std::mt19937_64 rng = test::seeded_rng(1807, "random arms and states");
  for (int arm = 0; arm < 20; ++arm) {
    const RobotModel model = load_text(random_arm_urdf(rng), "random_arm.urdf");
    expect_dynamics_match_kdl(model, rng, 200);
  }
}

TEST(RobotModel, PayloadAddsAPointMassAtTheTipOrigin) {
  const RobotModel& bare = bundled_model();
  const double mass = 12.5;
  const RobotModel loaded = bare.with_payload(mass);
  std::mt19937_64 rng = test::seeded_rng(7, "payload configurations");
  for (int k = 0; k < 200; ++k) {
    JointVector q{};
    for (std::size_t i = 0; i < kNumJoints; ++i)
      q[i] = uniform(rng, bare.lower_limits_rad()[i], bare.upper_limits_rad()[i]);
    // A point mass at the tip origin: kinetic energy ½ m |J_v q̇|², potential m g z_tip.
    const Eigen::Matrix<double, 3, 6> jv = jacobian_of(bare, q).topRows<3>();
    const Mat6 added = mass * jv.transpose() * jv;
    EXPECT_LT(relative_error(Mat6(mass_matrix_of(loaded, q) - mass_matrix_of(bare, q)), added),
              1e-12);
    const Vec6 added_g = mass * 9.81 * jv.transpose() * Eigen::Vector3d::UnitZ();
    EXPECT_LT(relative_error(
                  Vec6(to_vec(loaded.gravity_torque(q)) - to_vec(bare.gravity_torque(q))), added_g),
              1e-12);
    const JointVector diagonal = inertia_diagonal_of(loaded, q);
    for (std::size_t i = 0; i < kNumJoints; ++i)
      EXPECT_NEAR(diagonal[i],
                  inertia_diagonal_of(bare, q)[i] + added(static_cast<int>(i), static_cast<int>(i)),
                  1e-9);
    // The fast dynamics of the plant carry the payload too.
    EXPECT_LT(relative_error(detail::dynamics_of(loaded).mass_matrix(to_vec(q)),
                             mass_matrix_of(loaded, q)),
              1e-9);
  }
}

TEST(RobotModel, ZeroPayloadIsAnEqualCopy) {
  const RobotModel copy = bundled_model().with_payload(0.0);
  const JointVector q = {0.3, -1.2, 0.1, 0.5, -0.4, -1.5};
  const JointVector qd = {0.5, -0.4, 0.6, 1.0, -0.8, 1.2};
  EXPECT_EQ(mass_matrix_of(copy, q), mass_matrix_of(bundled_model(), q));
  EXPECT_EQ(copy.gravity_torque(q), bundled_model().gravity_torque(q));
  EXPECT_EQ(coriolis_of(copy, q, qd), coriolis_of(bundled_model(), q, qd));
  EXPECT_EQ(copy.robot_name(), bundled_model().robot_name());
}

TEST(RobotModel, NamesTheRobotAndItsContinuousJoints) {
  EXPECT_EQ(bundled_model().robot_name(), "er50_c20");
  for (std::size_t j = 0; j < kNumJoints; ++j)
    EXPECT_FALSE(bundled_model().continuous(j));
  EXPECT_FALSE(bundled_model().continuous(kNumJoints));
  std::ifstream in(default_urdf_path());
  std::stringstream text;
  text << in.rdbuf();
  std::string urdf = text.str();
  const std::string joint6 = "<joint name=\"joint6\" type=\"revolute\">";
  ASSERT_NE(urdf.find(joint6), std::string::npos);
  urdf.replace(urdf.find(joint6), joint6.size(), "<joint name=\"joint6\" type=\"continuous\">");
  const RobotModel model = load_text(urdf, "continuous_j6.urdf");
  EXPECT_TRUE(model.continuous(5));
  EXPECT_FALSE(model.continuous(4));
  EXPECT_EQ(model.upper_limits_rad()[5], std::numeric_limits<double>::infinity());
}

// A PD law toward a moving target, held over each tick: the closed loop the accuracy and cost
// figures are measured on (bench/bench_robot.cpp drives the plants the same way).
JointVector pd_torque(const JointPlant& plant, double t) {
  static constexpr JointVector kp = {6000.0, 12000.0, 3000.0, 300.0, 300.0, 60.0};
  static constexpr JointVector kd = {1200.0, 2400.0, 600.0, 60.0, 60.0, 12.0};
  JointVector tau{};
  for (std::size_t i = 0; i < kNumJoints; ++i) {
    const double target =
        kPaperStartJoints[i] + 0.5 * std::sin(1.3 * t + 0.4 * static_cast<double>(i));
    // What the drive measures: the joint, or the motor side of an elastic one.
    tau[i] = kp[i] * (target - plant.measured_position()[i]) - kd[i] * plant.measured_velocity()[i];
  }
  return tau;
}

// Largest |q − q_reference| over a 5 s run with gravity, each plant on its own PD loop.
// The coupled step settings scaled by `scale` (1: the defaults).
PlantConfig coupled_step(PlantConfig c, double substep_s, double step_rad, double scale) {
  c.coupling = PlantCoupling::Coupled;
  c.gravity = true;
  c.coupled_substep_s = substep_s * scale;
  c.coupled_step_rad = step_rad * scale;
  return c;
}

double coupled_run_error(double tick_s, double substep_s, double step_rad) {
  PlantConfig c;
  c.armature_kgm2 = kEr50ArmatureKgm2;  // the bundled ER50-C20 with its motors
  c.coupling = PlantCoupling::Coupled;
  c.gravity = true;
  c.damping_nms = {20.0, 30.0, 10.0, 1.0, 1.0, 0.2};
  JointPlant plant(bundled_model(), coupled_step(c, substep_s, step_rad, 1.0));
  JointPlant reference(bundled_model(), coupled_step(c, substep_s, step_rad, 0.1));
  plant.reset(kPaperStartJoints, JointVector{});
  reference.reset(kPaperStartJoints, JointVector{});
  double worst = 0.0;
  const int ticks = static_cast<int>(std::lround(5.0 / tick_s));
  for (int k = 0; k < ticks; ++k) {
    const double t = k * tick_s;
    EXPECT_NE(plant.step(pd_torque(plant, t), tick_s), PlantStatus::NumericalError);
    EXPECT_NE(reference.step(pd_torque(reference, t), tick_s), PlantStatus::NumericalError);
    for (std::size_t i = 0; i < kNumJoints; ++i)
      worst = std::max(worst, std::fabs(plant.position()[i] - reference.position()[i]));
  }
  return worst;
}

// The harder case for the step: no armature (a URDF other than the bundled one gets none by
// default), so the wrist's small link inertia sets the fastest time scale; a 20 kg payload; gravity
// compensated from the model and PD gains scaled to each joint's inertia, tracking 1 rad at
// 3 rad/s (3 rad/s peak, about the ER50 J1-J3 velocity limits). Largest |q − q_reference| over 5 s.
double bare_arm_run_error(double tick_s, double substep_s, double step_rad) {
  const RobotModel model = bundled_model().with_payload(20.0);
  PlantConfig c;
  c.coupling = PlantCoupling::Coupled;
  c.gravity = true;
  c.armature_kgm2 = {};
  c.torque_limit_nm = JointVector{1e9, 1e9, 1e9, 1e9, 1e9, 1e9};
  JointPlant plant(model, coupled_step(c, substep_s, step_rad, 1.0));
  JointPlant reference(model, coupled_step(c, substep_s, step_rad, 0.1));
  // Starts on the target with its velocity, so no step transient exceeds the velocity limits.
  const auto target = [](double t, JointVector& q, JointVector& qd) {
    for (std::size_t i = 0; i < kNumJoints; ++i) {
      const double phase = 3.0 * t + 0.4 * static_cast<double>(i);
      q[i] = kPaperStartJoints[i] + std::sin(phase);
      qd[i] = 3.0 * std::cos(phase);
    }
  };
  JointVector q0{};
  JointVector qd0{};
  target(0.0, q0, qd0);
  plant.reset(q0, qd0);
  reference.reset(q0, qd0);
  const Mat6 m = mass_matrix_of(model, q0);
  const double w = 0.25 / tick_s;  // closed-loop bandwidth, rad/s
  const auto law = [&](const JointPlant& p, double t) {
    JointVector tau = model.gravity_torque(p.position());
    JointVector q{};
    JointVector qd{};
    target(t, q, qd);
    for (std::size_t i = 0; i < kNumJoints; ++i) {
      const double j = m(static_cast<int>(i), static_cast<int>(i));
      tau[i] += j * w * w * (q[i] - p.position()[i]) + 1.6 * j * w * (qd[i] - p.velocity()[i]);
    }
    return tau;
  };
  double worst = 0.0;
  const int ticks = static_cast<int>(std::lround(5.0 / tick_s));
  for (int k = 0; k < ticks; ++k) {
    const double t = k * tick_s;
    EXPECT_NE(plant.step(law(plant, t), tick_s), PlantStatus::NumericalError);
    EXPECT_NE(reference.step(law(reference, t), tick_s), PlantStatus::NumericalError);
    for (std::size_t i = 0; i < kNumJoints; ++i)
      worst = std::max(worst, std::fabs(plant.position()[i] - reference.position()[i]));
  }
  return worst;
}

TEST(JointPlant, CoupledDefaultStepStaysWithinAMicroradianOfATenTimesFinerStep) {
  const PlantConfig d;
  for (double tick : {0.05, 0.01}) {
    const double error = coupled_run_error(tick, d.coupled_substep_s, d.coupled_step_rad);
    std::printf("[ accuracy ] PD loop, tick %.0f ms: max |q - q_ref| over 5 s %.2e rad\n",
                tick * 1e3, error);
    EXPECT_LT(error, 1e-6) << "tick " << tick;
  }
}

TEST(JointPlant, CoupledDefaultStepStaysWithinAMicroradianWithoutArmatureAtFullSpeed) {
  const PlantConfig d;
  for (double tick : {0.05, 0.01}) {
    const double error = bare_arm_run_error(tick, d.coupled_substep_s, d.coupled_step_rad);
    std::printf("[ accuracy ] no armature, tick %.0f ms: max |q - q_ref| over 5 s %.2e rad\n",
                tick * 1e3, error);
    EXPECT_LT(error, 1e-6) << "tick " << tick;
  }
}

// Every step setting divided by `scale` (1: the defaults).
PlantConfig scaled_steps(PlantConfig c, double scale) {
  const PlantConfig d;
  c.substep_s = d.substep_s * scale;
  c.coupled_substep_s = d.coupled_substep_s * scale;
  c.coupled_step_rad = d.coupled_step_rad * scale;
  c.step_rate_limit = d.step_rate_limit * scale;
  return c;
}

// Largest |q − q_reference| over a 5 s PD run (pd_torque) of `c` with the default steps against
// the same run with every step ten times finer.
double finer_step_error(const RobotModel& model, const PlantConfig& c, double tick_s) {
  JointPlant plant(model, scaled_steps(c, 1.0));
  JointPlant reference(model, scaled_steps(c, 0.1));
  plant.reset(kPaperStartJoints, JointVector{});
  reference.reset(kPaperStartJoints, JointVector{});
  double worst = 0.0;
  const int ticks = static_cast<int>(std::lround(5.0 / tick_s));
  for (int k = 0; k < ticks; ++k) {
    const double t = k * tick_s;
    EXPECT_NE(plant.step(pd_torque(plant, t), tick_s), PlantStatus::NumericalError);
    EXPECT_NE(reference.step(pd_torque(reference, t), tick_s), PlantStatus::NumericalError);
    for (std::size_t i = 0; i < kNumJoints; ++i)
      worst = std::max(worst, std::fabs(plant.position()[i] - reference.position()[i]));
  }
  return worst;
}

// Viscous friction of 100/s (b_i = 100 J_i, sim_ab --friction 100), and 5000/s decoupled: RK4 at
// the coupled 50 ms or the decoupled 1 ms step alone would be beyond its stable range
// (h·λ = 2.785).
TEST(JointPlant, HighFrictionDefaultStepStaysWithinAMicroradianOfATenTimesFinerStep) {
  const JointVector j = inertia_diagonal_of(bundled_model(), kPaperStartJoints);
  for (const auto& [coupling, friction] :
       {std::pair{PlantCoupling::Decoupled, 100.0}, std::pair{PlantCoupling::Decoupled, 5000.0},
        std::pair{PlantCoupling::Coupled, 100.0}}) {
    PlantConfig c;
    for (std::size_t i = 0; i < kNumJoints; ++i)
      c.damping_nms[i] = friction * (j[i] + c.armature_kgm2[i]);
    c.coupling = coupling;
    c.gravity = coupling == PlantCoupling::Coupled;
    for (double tick : {0.05, 0.01}) {
      const double error = finer_step_error(bundled_model(), c, tick);
      std::printf("[ accuracy ] friction %g/s, %s, tick %.0f ms: max |q - q_ref| %.2e rad\n",
                  friction, coupling == PlantCoupling::Coupled ? "coupled" : "decoupled",
                  tick * 1e3, error);
      EXPECT_LT(error, 1e-6) << "tick " << tick << ", friction " << friction;
    }
  }
}

// What real joints have. A decoupled plant with a fixed inertia and no friction is a double
// integrator per joint, J θ̈ = τ(t): with τ piecewise constant RK4 is exact, so closed forms hold
// to rounding.
PlantConfig double_integrator() {
  PlantConfig c;
  c.armature_kgm2 = kEr50ArmatureKgm2;  // the bundled ER50-C20's motors (a gear needs them)
  c.inertia_update = InertiaUpdate::Fixed;
  c.torque_limit_nm = JointVector{1e6, 1e6, 1e6, 1e6, 1e6, 1e6};
  return c;
}

// θ, θ̇ after `t` seconds of constant torque `tau` on inertia `j`.
void hold(double j, double tau, double t, double& th, double& w) {
  th += w * t + 0.5 * tau / j * t * t;
  w += tau / j * t;
}

JointVector tick_torque(int k) {
  JointVector tau{};
  for (std::size_t i = 0; i < kNumJoints; ++i)
    tau[i] = 50.0 * std::sin(0.7 * k + static_cast<double>(i)) + 5.0 * static_cast<double>(i);
  return tau;
}

TEST(JointPlant, ADelayOfOneTickIsThePreviousTicksTorque) {
  const double dt = 0.01;
  PlantConfig c = double_integrator();
  JointPlant plain(bundled_model(), c);
  c.delay_s = dt;
  JointPlant delayed(bundled_model(), c);
  plain.reset(kPaperStartJoints, JointVector{});
  delayed.reset(kPaperStartJoints, JointVector{});
  const JointVector j = plain.inertia();
  JointVector th = kPaperStartJoints;
  JointVector w{};
  for (int k = 0; k < 40; ++k) {
    const JointVector previous = k == 0 ? JointVector{} : tick_torque(k - 1);
    ASSERT_EQ(delayed.step(tick_torque(k), dt), PlantStatus::Ok);
    ASSERT_EQ(plain.step(previous, dt), PlantStatus::Ok);
    for (std::size_t i = 0; i < kNumJoints; ++i)
      hold(j[i], previous[i], dt, th[i], w[i]);
    EXPECT_EQ(delayed.applied_torque(), previous) << "tick " << k;
  }
  for (std::size_t i = 0; i < kNumJoints; ++i) {
    EXPECT_DOUBLE_EQ(delayed.position()[i], plain.position()[i]) << "joint " << i + 1;
    EXPECT_DOUBLE_EQ(delayed.velocity()[i], plain.velocity()[i]) << "joint " << i + 1;
    EXPECT_NEAR(delayed.position()[i], th[i], 1e-12) << "joint " << i + 1;
    EXPECT_NEAR(delayed.velocity()[i], w[i], 1e-12) << "joint " << i + 1;
  }
}

// D = n dt + f: over each tick the command of n + 1 ticks ago for f seconds, then that of n ticks
// ago (zero before the first command).
TEST(JointPlant, AFractionalDelaySwitchesTheTorqueWithinTheTick) {
  const double dt = 0.01;
  for (double ticks : {0.3, 1.3, 2.75}) {
    PlantConfig c = double_integrator();
    c.delay_s = ticks * dt;
    JointPlant plant(bundled_model(), c);
    plant.reset(JointVector{}, JointVector{});
    const JointVector j = plant.inertia();
    const int n = static_cast<int>(ticks);
    const double f = (ticks - n) * dt;
    const auto command = [](int k) { return k < 0 ? JointVector{} : tick_torque(k); };
    JointVector th{};
    JointVector w{};
    for (int k = 0; k < 30; ++k) {
      ASSERT_EQ(plant.step(tick_torque(k), dt), PlantStatus::Ok);
      for (std::size_t i = 0; i < kNumJoints; ++i) {
        hold(j[i], command(k - n - 1)[i], f, th[i], w[i]);
        hold(j[i], command(k - n)[i], dt - f, th[i], w[i]);
      }
    }
    for (std::size_t i = 0; i < kNumJoints; ++i) {
      EXPECT_NEAR(plant.position()[i], th[i], 1e-11) << ticks << " ticks, joint " << i + 1;
      EXPECT_NEAR(plant.velocity()[i], w[i], 1e-11) << ticks << " ticks, joint " << i + 1;
    }
  }
}

// A torque step through the current loop τ̇ = ω (u − τ) on J θ̈ = τ from rest:
// τ = u (1 − e^(−ωt)), θ̇ = u/J (t − (1 − e^(−ωt))/ω), θ = u/J (t²/2 − t/ω + (1 − e^(−ωt))/ω²).
TEST(JointPlant, TheCurrentLoopIsAFirstOrderLagDrivingTheJoint) {
  PlantConfig c = double_integrator();
  c.torque_bandwidth_hz = 8.0;
  JointPlant plant(bundled_model(), c);
  plant.reset(JointVector{}, JointVector{});
  const JointVector j = plant.inertia();
  const JointVector u = {100.0, -200.0, 50.0, 5.0, -3.0, 1.0};
  const double w = 2.0 * 3.14159265358979323846 * c.torque_bandwidth_hz;
  for (int k = 1; k <= 50; ++k) {
    ASSERT_EQ(plant.step(u, 0.01), PlantStatus::Ok);
    const double t = 0.01 * k;
    const double e = std::exp(-w * t);
    for (std::size_t i = 0; i < kNumJoints; ++i) {
      EXPECT_NEAR(plant.applied_torque()[i], u[i] * (1.0 - e), 1e-12 * std::fabs(u[i]));
      const double a = u[i] / j[i];
      EXPECT_NEAR(plant.velocity()[i], a * (t - (1.0 - e) / w), 1e-9 * std::fabs(a));
      EXPECT_NEAR(plant.position()[i], a * (0.5 * t * t - t / w + (1.0 - e) / (w * w)),
                  1e-9 * std::fabs(a));
    }
  }
}

// Friction torque F(θ̇) of joint i as plant.hpp writes it.
double friction_of(const PlantConfig& c, std::size_t i, double w) {
  const double cc = c.coulomb_nm[i];
  const double peak = std::max(c.stribeck_nm[i], cc);
  const double r = w / c.stribeck_velocity_rad_s;
  return std::tanh(w / c.coulomb_smoothing_rad_s) * (cc + (peak - cc) * std::exp(-r * r));
}

// The creep speed where F(θ̇) = tau, by bisection below the friction's peak.
double creep(const PlantConfig& c, std::size_t i, double tau) {
  double lo = 0.0;
  double hi = 5.0 * c.coulomb_smoothing_rad_s;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (friction_of(c, i, mid) < tau ? lo : hi) = mid;
  }
  return lo;
}

TEST(JointPlant, CoulombFrictionHoldsATorqueBelowItAndLetsThroughTheRest) {
  PlantConfig c = double_integrator();
  c.coulomb_nm = {40.0, 60.0, 20.0, 4.0, 3.0, 1.0};
  JointPlant plant(bundled_model(), c);
  // Half the friction: the joint creeps at v_ε atanh(1/2) = 0.55 mrad/s, the root of F = τ.
  plant.reset(JointVector{}, JointVector{});
  JointVector half{};
  for (std::size_t i = 0; i < kNumJoints; ++i)
    half[i] = 0.5 * c.coulomb_nm[i];
  for (int k = 0; k < 100; ++k)
    ASSERT_EQ(plant.step(half, 0.02), PlantStatus::Ok);
  const double bound = c.coulomb_smoothing_rad_s * std::atanh(0.5);
  for (std::size_t i = 0; i < kNumJoints; ++i) {
    EXPECT_NEAR(plant.velocity()[i], creep(c, i, half[i]), 1e-9) << "joint " << i + 1;
    EXPECT_NEAR(plant.velocity()[i], bound, 1e-9) << "joint " << i + 1;
    EXPECT_LT(plant.position()[i], 2.0 * bound) << "joint " << i + 1;  // over 2 s
  }
  // Three times the friction: (τ − C) / J once moving.
  JointPlant moving(bundled_model(), c);
  moving.reset(JointVector{}, JointVector{});
  const JointVector j = moving.inertia();
  JointVector triple{};
  for (std::size_t i = 0; i < kNumJoints; ++i)
    triple[i] = 3.0 * c.coulomb_nm[i];
  for (int k = 0; k < 50; ++k)
    ASSERT_EQ(moving.step(triple, 0.02), PlantStatus::Ok);
  const JointVector w1 = moving.velocity();
  for (int k = 0; k < 50; ++k)
    ASSERT_EQ(moving.step(triple, 0.02), PlantStatus::Ok);
  for (std::size_t i = 0; i < kNumJoints; ++i) {
    const double expected = 2.0 * c.coulomb_nm[i] / j[i];
    EXPECT_NEAR(moving.velocity()[i] - w1[i], expected * 1.0, 1e-9 * expected) << i + 1;
  }
}

// With a Stribeck peak S = 2 C, a torque between C and S still holds the joint (it creeps at the
// low root of F = τ); the plain Coulomb joint would accelerate.
TEST(JointPlant, AStribeckPeakHoldsATorqueBetweenCoulombAndThePeak) {
  PlantConfig c = double_integrator();
  c.coulomb_nm = {40.0, 60.0, 20.0, 4.0, 3.0, 1.0};
  for (std::size_t i = 0; i < kNumJoints; ++i)
    c.stribeck_nm[i] = 2.0 * c.coulomb_nm[i];
  JointPlant plant(bundled_model(), c);
  plant.reset(JointVector{}, JointVector{});
  JointVector tau{};
  for (std::size_t i = 0; i < kNumJoints; ++i)
    tau[i] = 1.5 * c.coulomb_nm[i];
  for (int k = 0; k < 100; ++k)
    ASSERT_EQ(plant.step(tau, 0.02), PlantStatus::Ok);
  for (std::size_t i = 0; i < kNumJoints; ++i) {
    EXPECT_NEAR(plant.velocity()[i], creep(c, i, tau[i]), 1e-9) << "joint " << i + 1;
    EXPECT_LT(plant.velocity()[i], c.coulomb_smoothing_rad_s) << "joint " << i + 1;
  }
}

TEST(JointPlant, AnEncoderQuantisesTheAngleAndDifferencesItForTheRate) {
  PlantConfig c = double_integrator();
  c.encoder_counts = 1000;  // 2π/1000 = 6.2832 mrad a count
  JointPlant plant(bundled_model(), c);
  const JointVector q0 = {0.3, -0.3, 0.0031, 0.0032, 1.0, -2.0};
  plant.reset(q0, {1.0, 1.0, 0.0, 0.0, 0.0, 0.0});
  const double count = 2.0 * 3.14159265358979323846 / 1000.0;
  // 0.3 rad = 47.75 counts -> 48; 0.0031 = 0.49 -> 0; 0.0032 = 0.51 -> 1; 1 = 159.15 -> 159.
  const std::array<double, kNumJoints> counts = {48, -48, 0, 1, 159, -318};
  for (std::size_t i = 0; i < kNumJoints; ++i)
    EXPECT_DOUBLE_EQ(plant.measured_position()[i], counts[i] * count) << "joint " << i + 1;
  EXPECT_EQ(plant.measured_velocity(), plant.velocity());  // the true rate right after reset
  EXPECT_EQ(plant.position(), q0);                         // the true angle is untouched
  // 10 ms at 1 rad/s: 0.31 rad = 49.34 counts -> 49, one count in 10 ms: 0.628 rad/s.
  ASSERT_EQ(plant.step(JointVector{}, 0.01), PlantStatus::Ok);
  EXPECT_DOUBLE_EQ(plant.measured_position()[0], 49 * count);
  EXPECT_DOUBLE_EQ(plant.measured_velocity()[0], (49 * count - 48 * count) / 0.01);
  EXPECT_DOUBLE_EQ(plant.measured_position()[1], -46 * count);  // -0.29 rad = -46.15 counts
  EXPECT_EQ(plant.measured_velocity()[2], 0.0);
}

// A constant torque τ on the undamped two-mass joint from rest: the gear's deflection
// δ = θ_m − θ obeys δ̈ = τ / J_m − ω² δ, so δ(t) = τ / (J_m ω²) (1 − cos ωt) at ω = 2π F.
TEST(JointPlant, AnElasticJointOscillatesFreelyAtItsResonance) {
  PlantConfig c = double_integrator();
  c.joint_resonance_hz = {20.0, 20.0, 35.0, 50.0, 0.0, 15.0};
  JointPlant plant(bundled_model(), c);
  ASSERT_TRUE(plant.valid());
  plant.reset(kPaperStartJoints, JointVector{});
  const JointVector tau = {100.0, -200.0, 50.0, 5.0, -3.0, 1.0};
  const double dt = 0.001;
  std::array<int, kNumJoints> crossings{};
  std::array<double, kNumJoints> first{}, last{};
  JointVector previous{};
  for (int k = 1; k <= 2000; ++k) {
    ASSERT_EQ(plant.step(tau, dt), PlantStatus::Ok);
    const double t = k * dt;
    for (std::size_t i = 0; i < kNumJoints; ++i) {
      const double delta = plant.motor_position()[i] - plant.position()[i];
      if (c.joint_resonance_hz[i] == 0.0) {
        EXPECT_EQ(delta, 0.0) << "joint " << i + 1 << " is rigid";
        continue;
      }
      const double w = 2.0 * 3.14159265358979323846 * c.joint_resonance_hz[i];
      const double amplitude = tau[i] / (c.armature_kgm2[i] * w * w);
      EXPECT_NEAR(delta, amplitude * (1.0 - std::cos(w * t)), 5e-3 * std::fabs(amplitude))
          << "joint " << i + 1 << ", t = " << t;
      // Upward crossings of the mean deflection, interpolated: whole periods between them.
      const double now = delta / amplitude - 1.0;
      if (k > 1 && previous[i] < 0.0 && now >= 0.0) {
        const double at = t - dt * now / (now - previous[i]);
        if (crossings[i]++ == 0) first[i] = at;
        last[i] = at;
      }
      previous[i] = now;
    }
  }
  for (std::size_t i = 0; i < kNumJoints; ++i) {
    if (c.joint_resonance_hz[i] == 0.0) continue;
    ASSERT_GT(crossings[i], 10);
    const double frequency = (crossings[i] - 1) / (last[i] - first[i]);
    EXPECT_NEAR(frequency, c.joint_resonance_hz[i], 0.01 * c.joint_resonance_hz[i]) << i + 1;
  }
  // The drive measures the motor side; the acceleration is the link's, τ_g / J_l (a rigid joint's
  // τ / J).
  EXPECT_EQ(plant.measured_position(), plant.motor_position());
  const JointVector j = plant.inertia();
  for (std::size_t i = 0; i < kNumJoints; ++i) {
    const double delta = plant.motor_position()[i] - plant.position()[i];
    const double w = 2.0 * 3.14159265358979323846 * c.joint_resonance_hz[i];
    const double jm = c.armature_kgm2[i];
    const double jl = j[i] - jm;
    const double expected =
        c.joint_resonance_hz[i] == 0.0 ? tau[i] / j[i] : w * w / (1.0 / jm + 1.0 / jl) * delta / jl;
    EXPECT_NEAR(plant.acceleration()[i], expected, 1e-9 * std::fabs(expected) + 1e-12) << i + 1;
  }
}

// Backlash B: from rest under a constant torque the motor turns freely (θ_m = ½ τ/J_m t²) and the
// link does not move at all until the play B/2 is taken up at t* = √(B J_m / τ); then it follows.
TEST(JointPlant, BacklashLetsTheMotorTurnFreelyUntilThePlayIsTakenUp) {
  PlantConfig c = double_integrator();
  c.joint_resonance_hz.fill(20.0);
  c.backlash_rad = 0.01;
  JointPlant plant(bundled_model(), c);
  ASSERT_TRUE(plant.valid());
  plant.reset(JointVector{}, JointVector{});
  const JointVector tau = {100.0, -200.0, 50.0, 5.0, -3.0, 1.0};
  const double dt = 0.001;
  for (int k = 1; k <= 400; ++k) {
    ASSERT_EQ(plant.step(tau, dt), PlantStatus::Ok);
    const double t = k * dt;
    for (std::size_t i = 0; i < kNumJoints; ++i) {
      const double jm = c.armature_kgm2[i];
      const double contact = std::sqrt(c.backlash_rad * jm / std::fabs(tau[i]));
      if (t < contact - dt) {
        EXPECT_EQ(plant.position()[i], 0.0) << "joint " << i + 1 << ", t = " << t;
        EXPECT_NEAR(plant.motor_position()[i], 0.5 * tau[i] / jm * t * t, 1e-12)
            << "joint " << i + 1 << ", t = " << t;
      }
    }
  }
  for (std::size_t i = 0; i < kNumJoints; ++i)  // every joint has made contact and moves
    EXPECT_GT(plant.position()[i] * tau[i], 0.0) << "joint " << i + 1;
  PlantConfig rigid = c;
  rigid.joint_resonance_hz = {};
  EXPECT_FALSE(JointPlant(bundled_model(), rigid).valid());  // backlash needs the gear
}

TEST(JointPlant, ElasticJointsNeedAnArmature) {
  PlantConfig c;
  c.armature_kgm2 = {8.5, 0.0, 5.4, 1.7, 1.7, 0.5};
  c.joint_resonance_hz = {20.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  EXPECT_TRUE(JointPlant(bundled_model(), c).valid());
  c.joint_resonance_hz[1] = 20.0;
  EXPECT_FALSE(JointPlant(bundled_model(), c).valid());
}

// A 20 Hz gear (ζ = 0.05) on every joint: the default step (h ω <= 0.25) against ten times finer.
TEST(JointPlant, ResonantGearDefaultStepStaysWithinAMicroradianOfATenTimesFinerStep) {
  PlantConfig c;
  c.joint_resonance_hz.fill(20.0);
  c.joint_damping_ratio = 0.05;
  for (PlantCoupling coupling : {PlantCoupling::Decoupled, PlantCoupling::Coupled}) {
    c.coupling = coupling;
    c.gravity = coupling == PlantCoupling::Coupled;
    for (double tick : {0.05, 0.01}) {
      const double error = finer_step_error(bundled_model(), c, tick);
      std::printf("[ accuracy ] 20 Hz gear, %s, tick %.0f ms: max |q - q_ref| %.2e rad\n",
                  coupling == PlantCoupling::Coupled ? "coupled" : "decoupled", tick * 1e3, error);
      EXPECT_LT(error, 1e-6) << "tick " << tick;
    }
  }
}

TEST(JointPlant, CoupledAccelerationIsTheDynamicsAtTheEndOfTheTick) {
  PlantConfig c;
  c.coupling = PlantCoupling::Coupled;
  c.gravity = true;
  c.inertia_scale = {1.0, 1.5, 0.5, 1.0, 2.0, 1.0};
  c.damping_nms = {20.0, 30.0, 10.0, 1.0, 1.0, 0.2};
  JointPlant plant(bundled_model(), c);
  plant.reset(kPaperStartJoints, {0.2, -0.1, 0.3, 0.5, -0.4, 1.0});
  const JointVector tau = {300.0, -1500.0, 400.0, 10.0, -5.0, 2.0};
  const JointVector disturbance = {5.0, 0.0, 0.0, 0.0, 0.0, -1.0};
  ASSERT_EQ(plant.step(tau, 0.05, disturbance), PlantStatus::Ok);
  const JointVector& q = plant.position();
  const JointVector& qd = plant.velocity();
  const Vec6 s = to_vec(c.inertia_scale).cwiseSqrt();
  Mat6 m = s.asDiagonal() * mass_matrix_of(bundled_model(), q) * s.asDiagonal();
  m.diagonal() += to_vec(c.armature_kgm2);
  const Vec6 rhs = to_vec(tau) + to_vec(disturbance) - to_vec(coriolis_of(bundled_model(), q, qd)) -
                   to_vec(bundled_model().gravity_torque(q)) -
                   to_vec(c.damping_nms).cwiseProduct(to_vec(qd));
  const Vec6 expected = m.llt().solve(rhs);
  EXPECT_LT(relative_error(to_vec(plant.acceleration()), expected), 1e-9);
  const JointPlant copy = plant;
  EXPECT_EQ(copy.acceleration(), plant.acceleration());
  plant.reset(q, qd);
  EXPECT_EQ(plant.acceleration(), JointVector{});
}

}  // namespace
}  // namespace fuzzypid::robot
