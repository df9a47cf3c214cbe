// The real-time calls allocate nothing after construction. Global operator new/delete are replaced
// by counting versions, which is why this test is its own executable.
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <new>

#include <gtest/gtest.h>

#include "fuzzypid/robot/analytic_ik.hpp"
#include "fuzzypid/robot/path.hpp"
#include "fuzzypid/robot/plant.hpp"
#include "fuzzypid/robot/robot_model.hpp"

namespace {
std::atomic<long> g_allocations{0};

void* counted_malloc(std::size_t size) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size == 0 ? 1 : size);
}

void* counted_aligned(std::size_t size, std::align_val_t alignment) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  const auto a = static_cast<std::size_t>(alignment);
  return std::aligned_alloc(a, ((size == 0 ? 1 : size) + a - 1) / a * a);
}

// Out of line so that GCC does not pair an inlined free() with a visible operator new and warn
// (-Wmismatched-new-delete).
[[gnu::noinline]] void release(void* p) noexcept {
  std::free(p);
}
}  // namespace

void* operator new(std::size_t size) {
  if (void* p = counted_malloc(size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
  return operator new(size);
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  return counted_malloc(size);
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  return counted_malloc(size);
}
void* operator new(std::size_t size, std::align_val_t a) {
  if (void* p = counted_aligned(size, a)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size, std::align_val_t a) {
  return operator new(size, a);
}
void operator delete(void* p) noexcept {
  release(p);
}
void operator delete[](void* p) noexcept {
  release(p);
}
void operator delete(void* p, std::size_t) noexcept {
  release(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  release(p);
}
void operator delete(void* p, std::align_val_t) noexcept {
  release(p);
}
void operator delete[](void* p, std::align_val_t) noexcept {
  release(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
  release(p);
}
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept {
  release(p);
}

namespace fuzzypid::robot {
namespace {

const RobotModel& model() {
  static const RobotModel m = *RobotModel::load(default_urdf_path()).model;
  return m;
}

class AllocationCounter {
 public:
  AllocationCounter() : start_(g_allocations.load()) {}
  long count() const { return g_allocations.load() - start_; }

 private:
  long start_;
};

TEST(NoAllocation, CountingOperatorNewSeesAllocations) {
  AllocationCounter c;
  void* volatile p = ::operator new(16);  // an explicit call cannot be elided
  ::operator delete(p);
  EXPECT_EQ(c.count(), 1);
}

TEST(NoAllocation, DecoupledPlantStep) {
  JointPlant plant(model());
  plant.reset(kPaperStartJoints, JointVector{});
  AllocationCounter c;
  for (int k = 0; k < 100; ++k) {
    (void)plant.step({100, -50, 20, 1, 1, 0.5}, 0.05, {1, 0, 0, 0, 0, 0});
  }
  (void)plant.step({0, 0, 0, 0, 0, 0}, -1.0);  // the rejection path too
  EXPECT_EQ(c.count(), 0);
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
  EXPECT_EQ(c.count(), 0);
}

TEST(NoAllocation, KinematicsAndDynamicsQueries) {
  const RobotModel& m = model();
  const JointVector q = {0.1, -0.2, 0.3, -0.4, 0.5, -0.6};
  AllocationCounter c;
  double sink = 0.0;
  for (int k = 0; k < 100; ++k) {
    sink += m.forward_kinematics(q).position_m.x();
    sink += m.jacobian(q)(0, 0);
    sink += m.mass_matrix(q)(0, 0);
    sink += m.inertia_diagonal(q)[1];
    sink += m.coriolis_torque(q, q)[2];
    sink += m.gravity_torque(q)[1];
  }
  EXPECT_EQ(c.count(), 0);
  EXPECT_TRUE(sink != 0.0);
}

TEST(NoAllocation, ClosedFormIkSolve) {
  const auto ik = AnalyticIk::from_model(model());
  ASSERT_TRUE(ik.has_value());
  const Pose target = model().forward_kinematics({0.1, -0.2, 0.3, -0.4, 0.5, -0.6});
  JointVector out{};
  AllocationCounter c;
  int ok = 0;
  for (int k = 0; k < 100; ++k)
    ok += ik->solve(target, JointVector{}, out) == IkStatus::Ok;
  (void)ik->solve_all(target);
  EXPECT_EQ(c.count(), 0);
  EXPECT_EQ(ok, 100);
}

}  // namespace
}  // namespace fuzzypid::robot
