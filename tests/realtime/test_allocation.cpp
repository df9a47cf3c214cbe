// The control path never allocates: every global allocation function is replaced by a counting
// one, and the counter must not move across 100,000 ticks of each per-tick call.
//
// This file replaces ::operator new/delete for its whole executable, so it is built on its own.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <new>
#include <random>
#include <string>

#include "fuzzypid/paper.hpp"
#include "fuzzypid/pid/pid.hpp"
#include "fuzzypid/supervisor/joint_controller.hpp"
#include "fuzzypid_support/counting_new.hpp"
#include "fuzzypid_support/uniform_real.hpp"

namespace {

using fuzzypid::Status;
using fuzzypid::supervisor::JointController;
using fuzzypid::supervisor::JointInput;

using fuzzypid::support::allocation_count;

constexpr int kTicks = 100000;
constexpr std::uint64_t kSeed = 0xa110c;

// Sinks the compiler cannot see through, so allocations in the positive control are not elided.
int* volatile g_int_sink = nullptr;
void* volatile g_sink = nullptr;

struct alignas(64) OverAligned {
  double x[8];
};

TEST(Allocation, TheCounterCountsEveryFormOfNew) {
  const std::size_t start = allocation_count();
  g_int_sink = new int(42);
  EXPECT_EQ(allocation_count(), start + 1);
  delete g_int_sink;
  g_int_sink = new int[4];
  EXPECT_EQ(allocation_count(), start + 2);
  delete[] g_int_sink;
  g_int_sink = new (std::nothrow) int(7);
  EXPECT_EQ(allocation_count(), start + 3);
  delete g_int_sink;
  auto* aligned = new OverAligned;
  g_sink = aligned;
  EXPECT_EQ(allocation_count(), start + 4);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(aligned) % 64, 0u);
  delete aligned;
  auto* aligned_array = new OverAligned[3];
  g_sink = aligned_array;
  EXPECT_EQ(allocation_count(), start + 5);
  delete[] aligned_array;
  {
    std::string heap(1000, 'x');  // a library allocation goes through the same functions
    g_sink = heap.data();
    EXPECT_EQ(allocation_count(), start + 6);
  }
}

// Varying joint states, drawn before the measured region.
struct Trajectory {
  static constexpr std::size_t kSamples = 1024;  // a power of two, indexed with a mask
  std::array<std::array<double, 6>, kSamples> qd{}, vd{}, q{}, v{};
  explicit Trajectory(std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    fuzzypid::support::UniformReal<double> u(-0.5, 0.5);
    for (std::size_t k = 0; k < kSamples; ++k)
      for (std::size_t i = 0; i < 6; ++i) {
        qd[k][i] = u(rng);
        vd[k][i] = u(rng);
        q[k][i] = u(rng);
        v[k][i] = u(rng);
      }
  }
};

void report(const char* what, std::size_t allocations, std::uint64_t seed) {
  const double per_tick = static_cast<double>(allocations) / kTicks;
  ::testing::Test::RecordProperty(std::string(what) + "_allocations",
                                  static_cast<int>(allocations));
  std::cout << "[ alloc    ] " << what << ": " << allocations << " allocations over " << kTicks
            << " ticks (" << per_tick << " per tick), seed " << seed << "\n";
}

TEST(Allocation, JointControllerFuzzyTicksNeverAllocate) {
  const auto trajectory = std::make_unique<Trajectory>(kSeed);
  SCOPED_TRACE("seed " + std::to_string(kSeed));
  const std::size_t before_construction = allocation_count();
  auto controller = fuzzypid::paper::make_joint_controller<double, 6>();
  EXPECT_EQ(allocation_count(), before_construction);
  const std::array<double, 6> feed_forward{0.1, -0.1, 0.2, -0.2, 0.0, 0.3};
  const std::array<double, 6> zero{};

  Status worst = Status::Ok;
  double checksum = 0.0;
  const std::size_t start = allocation_count();
  for (int k = 0; k < kTicks; ++k) {
    const std::size_t s = static_cast<std::size_t>(k) & (Trajectory::kSamples - 1);
    const auto out = controller.step(
        JointInput<double, 6>{trajectory->qd[s], trajectory->vd[s], trajectory->q[s],
                              trajectory->v[s], k % 2 == 0 ? feed_forward : zero},
        0.05);
    worst = fuzzypid::worst(worst, out.status);
    checksum += out.output[k % 6] + controller.joint(k % 6).gains().kd;
  }
  const std::size_t allocations = allocation_count() - start;
  report("joint_controller_fuzzy", allocations, kSeed);
  EXPECT_EQ(allocations, 0u);
  EXPECT_EQ(worst, Status::Ok);
  EXPECT_TRUE(std::isfinite(checksum));
}

TEST(Allocation, FaultyTicksNeverAllocateEither) {
  auto controller = fuzzypid::paper::make_joint_controller<double, 6>();
  std::array<double, 6> qd{}, vd{}, q{}, v{};
  q[3] = std::nan("");
  const std::size_t start = allocation_count();
  Status worst = Status::Ok;
  for (int k = 0; k < kTicks; ++k) {
    qd[0] = 1e-5 * k;
    worst = fuzzypid::worst(
        worst,
        controller.step(JointInput<double, 6>{qd, vd, q, v}, k % 3 == 0 ? 0.0 : 0.05).status);
  }
  EXPECT_EQ(allocation_count() - start, 0u);
  EXPECT_TRUE(fuzzypid::is_fault(worst));
}

TEST(Allocation, PidTicksNeverAllocate) {
  fuzzypid::pid::Config<double> config;
  config.gains = {4.0, 0.001, 100.0};
  config.derivative_source = fuzzypid::pid::DerivativeSource::Difference;
  config.derivative_filter_s = 0.01;
  config.output_min = -10.0;
  config.output_max = 10.0;
  fuzzypid::pid::Pid<double> pid(config);
  JointController<double, 6, fuzzypid::pid::Pid<double>> joints(pid);
  const auto trajectory = std::make_unique<Trajectory>(kSeed + 1);
  double checksum = 0.0;
  const std::size_t start = allocation_count();
  for (int k = 0; k < kTicks; ++k) {
    const std::size_t s = static_cast<std::size_t>(k) & (Trajectory::kSamples - 1);
    fuzzypid::pid::Input<double> in;
    in.setpoint = trajectory->qd[s][0];
    in.measurement = trajectory->q[s][0];
    (void)pid.update(in, 0.001);
    const auto out = joints.step(JointInput<double, 6>{trajectory->qd[s], trajectory->vd[s],
                                                       trajectory->q[s], trajectory->v[s]},
                                 0.001);
    checksum += pid.output() + out.output[5];
  }
  const std::size_t allocations = allocation_count() - start;
  report("pid", allocations, kSeed + 1);
  EXPECT_EQ(allocations, 0u);
  EXPECT_TRUE(std::isfinite(checksum));
}

TEST(Allocation, PaperSystemInferenceNeverAllocates) {
  const auto system_min = fuzzypid::paper::make_system<double>();
  const auto system_prod =
      fuzzypid::paper::make_system<float>(fuzzypid::fuzzy::Conjunction::Product);
  std::mt19937_64 rng(kSeed + 2);
  fuzzypid::support::UniformReal<double> u(-0.4, 0.4);
  std::array<double, 1024> e{}, ec{};
  for (std::size_t k = 0; k < e.size(); ++k) {
    e[k] = u(rng);
    ec[k] = u(rng);
  }
  double checksum = 0.0;
  auto workspace = system_min.make_workspace();
  const std::size_t start = allocation_count();
  for (int k = 0; k < kTicks; ++k) {
    const std::size_t s = static_cast<std::size_t>(k) & 1023u;
    const auto r = system_min.infer(e[s], ec[s]);
    const auto f = system_prod.infer(static_cast<float>(e[s]), static_cast<float>(ec[s]));
    std::array<double, 3> delta{};
    fuzzypid::paper::System<double>::Trace trace;
    const Status traced = system_min.infer(e[s], ec[s], workspace, delta, trace);
    checksum += r.output[0] + r.firing_strength(3, 3) + static_cast<double>(f.output[2]) +
                delta[1] + trace.total_strength + static_cast<double>(traced);
  }
  const std::size_t allocations = allocation_count() - start;
  report("paper_system_infer", allocations, kSeed + 2);
  EXPECT_EQ(allocations, 0u);
  EXPECT_TRUE(std::isfinite(checksum));
}

TEST(Allocation, FloatFuzzyJointControllerNeverAllocates) {
  auto controller = fuzzypid::paper::make_joint_controller<float, 6>();
  std::array<float, 6> qd{}, vd{}, q{}, v{};
  const std::size_t start = allocation_count();
  float checksum = 0.0f;
  for (int k = 0; k < kTicks; ++k) {
    for (std::size_t i = 0; i < 6; ++i) {
      qd[i] = 0.3f * std::sin(0.001f * static_cast<float>(k) + static_cast<float>(i));
      q[i] = 0.5f * qd[i];
      v[i] = -0.1f * qd[i];
    }
    JointInput<float, 6> in;
    in.desired_position_rad = qd;
    in.desired_velocity_rad_s = vd;
    in.measured_position_rad = q;
    in.measured_velocity_rad_s = v;
    checksum += controller.step(in, 0.05f).output[k % 6];
  }
  EXPECT_EQ(allocation_count() - start, 0u);
  EXPECT_TRUE(std::isfinite(checksum));
}

}  // namespace
