// The real-time calls allocate nothing after construction. Global operator new/delete are replaced
// by counting versions, which is why this test is its own executable.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <new>

#include <gtest/gtest.h>

#include "fuzzypid/robot/analytic_ik.hpp"
#include "fuzzypid/robot/path.hpp"
#include "fuzzypid/robot/plant.hpp"
#include "fuzzypid/robot/robot_model.hpp"
#include "fuzzypid_support/counting_new.hpp"

namespace fuzzypid::robot {
namespace {

const RobotModel& model() {
  static const RobotModel m = *RobotModel::load(default_urdf_path()).model;
  return m;
}

class AllocationCounter {
 public:
  AllocationCounter() : start_(support::allocation_count()) {}
  std::uint64_t count() const { return support::allocation_count() - start_; }

 private:
  std::uint64_t start_;
};

TEST(NoAllocation, CountingOperatorNewSeesAllocations) {
  AllocationCounter c;
  void* volatile p = ::operator new(16);  // an explicit call cannot be elided
  ::operator delete(p);
  EXPECT_EQ(c.count(), 1u);
}

TEST(NoAllocation, DecoupledPlantStep) {
  JointPlant plant(model());
  plant.reset(kPaperStartJoints, JointVector{});
  AllocationCounter c;
  for (int k = 0; k < 100; ++k) {
    (void)plant.step({100, -50, 20, 1, 1, 0.5}, 0.05, {1, 0, 0, 0, 0, 0});
  }
  (void)plant.step({0, 0, 0, 0, 0, 0}, -1.0);  // the rejection path too
  EXPECT_EQ(c.count(), 0u);
}

TEST(NoAllocation, CoupledPlantStepWithGravity) {
  PlantConfig config;
  config.coupling = PlantCoupling::Coupled;
  config.gravity = true;
  JointPlant plant(model(), config);
  plant.reset(kPaperStartJoints, JointVector{});
  AllocationCounter c;
  for (int k = 0; k < 20; ++k)
    (void)plant.step({100, -50, 20, 1, 1, 0.5}, 0.05);
  EXPECT_EQ(c.count(), 0u);
}

TEST(NoAllocation, CoupledPlantStepWithPayloadGravityAndFixedInertia) {
  const RobotModel loaded = model().with_payload(20.0);
  PlantConfig config;
  config.coupling = PlantCoupling::Coupled;
  config.gravity = true;
  config.damping_nms = {20.0, 30.0, 10.0, 1.0, 1.0, 0.2};
  JointPlant every_tick(loaded, config);
  config.inertia_update = InertiaUpdate::Fixed;
  JointPlant fixed(loaded, config);
  every_tick.reset(kPaperStartJoints, {0.5, -0.5, 0.5, 1.0, -1.0, 2.0});
  fixed.reset(kPaperStartJoints, JointVector{});
  AllocationCounter c;
  for (int k = 0; k < 50; ++k) {
    (void)every_tick.step({100, -50, 20, 1, 1, 0.5}, 0.01, {1, 0, 0, 0, 0, 0});
    (void)fixed.step({100, -50, 20, 1, 1, 0.5}, 0.05);
    EXPECT_TRUE(std::isfinite(every_tick.acceleration()[0]));
  }
  (void)fixed.step({0, 0, 0, 0, 0, 0}, -1.0);  // the rejection path too
  EXPECT_EQ(c.count(), 0u);
}

// The stiffness bound of the step (an eigenvalue problem per tick in coupled mode).
TEST(NoAllocation, PlantStepsWithHighViscousFriction) {
  PlantConfig config;
  config.damping_nms = {3000.0, 5000.0, 1000.0, 100.0, 100.0, 30.0};
  JointPlant decoupled(model(), config);
  config.coupling = PlantCoupling::Coupled;
  config.gravity = true;
  JointPlant coupled(model(), config);
  decoupled.reset(kPaperStartJoints, JointVector{});
  coupled.reset(kPaperStartJoints, JointVector{});
  AllocationCounter c;
  for (int k = 0; k < 20; ++k) {
    (void)decoupled.step({100, -50, 20, 1, 1, 0.5}, 0.05);
    (void)coupled.step({100, -50, 20, 1, 1, 0.5}, 0.05);
  }
  EXPECT_EQ(c.count(), 0u);
}

// What real joints have: a fractional delay (the step cut in two), the current loop, Coulomb and
// Stribeck friction, an encoder and elastic joints beside rigid ones.
TEST(NoAllocation, PlantStepsWithEveryJointEffect) {
  PlantConfig config;
  config.delay_s = 0.0123;
  config.torque_bandwidth_hz = 50.0;
  config.coulomb_nm = {20.0, 30.0, 10.0, 1.0, 1.0, 0.2};
  config.stribeck_nm = {30.0, 45.0, 15.0, 1.5, 1.5, 0.3};
  config.encoder_counts = 1u << 17;
  config.joint_resonance_hz = {20.0, 20.0, 30.0, 0.0, 0.0, 40.0};
  config.joint_damping_ratio = 0.05;
  JointPlant decoupled(model(), config);
  config.coupling = PlantCoupling::Coupled;
  config.gravity = true;
  JointPlant coupled(model(), config);
  decoupled.reset(kPaperStartJoints, JointVector{});
  coupled.reset(kPaperStartJoints, JointVector{});
  AllocationCounter c;
  for (int k = 0; k < 5; ++k) {
    (void)decoupled.step({100, -50, 20, 1, 1, 0.5}, 0.01);
    (void)coupled.step({100, -50, 20, 1, 1, 0.5}, 0.01);
    EXPECT_TRUE(std::isfinite(decoupled.measured_velocity()[0]));
  }
  EXPECT_EQ(c.count(), 0u);
}

// The queries allocate nothing once the caller's RobotData is made (set-up: it allocates).
TEST(NoAllocation, KinematicsAndDynamicsQueries) {
  const RobotModel& m = model();
  RobotData data(m);
  const JointVector q = {0.1, -0.2, 0.3, -0.4, 0.5, -0.6};
  AllocationCounter c;
  double sink = 0.0;
  for (int k = 0; k < 100; ++k) {
    sink += m.forward_kinematics(q, data).position_m.x();
    sink += m.jacobian(q, data)(0, 0);
    sink += m.mass_matrix(q, data)(0, 0);
    sink += m.inertia_diagonal(q, data)[1];
    sink += m.coriolis_torque(q, q, data)[2];
    sink += m.gravity_torque(q)[1];
  }
  EXPECT_EQ(c.count(), 0u);
  EXPECT_TRUE(sink != 0.0);
}

TEST(NoAllocation, ClosedFormIkSolve) {
  const auto ik = AnalyticIk::from_model(model());
  ASSERT_TRUE(ik.has_value());
  RobotData data(model());
  const Pose target = model().forward_kinematics({0.1, -0.2, 0.3, -0.4, 0.5, -0.6}, data);
  JointVector out{};
  AllocationCounter c;
  int ok = 0;
  for (int k = 0; k < 100; ++k)
    ok += ik->solve(target, JointVector{}, out) == IkStatus::Ok;
  (void)ik->solve_all(target);
  EXPECT_EQ(c.count(), 0u);
  EXPECT_EQ(ok, 100);
}

}  // namespace
}  // namespace fuzzypid::robot
