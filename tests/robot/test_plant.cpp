// The joint plant: RK4 under zero-order hold, inertia from the model, saturation, bad input.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "fuzzypid/robot/path.hpp"
#include "fuzzypid/robot/plant.hpp"
#include "test_support.hpp"

namespace fuzzypid::robot {
namespace {

using test::bundled_model;

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
  const JointVector d0 = bundled_model().inertia_diagonal(q0);
  for (std::size_t i = 0; i < kNumJoints; ++i) {
    EXPECT_DOUBLE_EQ(plant.inertia()[i], c.inertia_scale[i] * d0[i] + c.armature_kgm2[i]);
  }
  const JointVector q1 = plant.position();
  ASSERT_EQ(plant.step(tau, 0.05), PlantStatus::Ok);
  const JointVector d1 = bundled_model().inertia_diagonal(q1);
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
    Eigen::Matrix<double, 6, 6> m = bundled_model().mass_matrix(q);
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

}  // namespace
}  // namespace fuzzypid::robot
