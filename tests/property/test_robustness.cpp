// Bad input over many ticks, without the robot part: six fuzzy PIDs (absolute and incremental gain
// update) on unit double integrators, fed jittered and invalid time steps, NaN/inf/huge
// measurements and setpoint jumps from a seeded std::mt19937_64. These back the rows of
// docs/robustness.md for the core alone; apps/soak repeats the abuse on the arm's plant.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>

#include "fuzzypid/paper.hpp"
#include "fuzzypid/pid/pid.hpp"
#include "fuzzypid/status.hpp"
#include "fuzzypid/supervisor/fuzzy_pid.hpp"
#include "fuzzypid/supervisor/joint_controller.hpp"

namespace {

using fuzzypid::Status;
using Fuzzy = fuzzypid::paper::FuzzyPid<double>;
using Controller = fuzzypid::supervisor::JointController<double, 6, Fuzzy>;
using Vector = Controller::Vector;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kOutputLimit = 5.0;  // rad/s²
constexpr double kIntegralLimit = 2.0;

// Uniform [0, 1) from the engine's bits: the same sequence with every standard library.
double uniform(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

fuzzypid::supervisor::FuzzyPidConfig<double> config(std::size_t joint) {
  auto c = fuzzypid::paper::paper_config<double>();
  c.pid.gains = {4.0, 0.02, 5.0};  // the paper's per-tick gains at 50 ms, continuous form
  c.pid.output_min = -kOutputLimit;
  c.pid.output_max = kOutputLimit;
  c.pid.integral_min = -kIntegralLimit;
  c.pid.integral_max = kIntegralLimit;
  c.output_scale = {1.0, 20.0, 0.05};
  c.gain_update = joint % 2 == 0 ? fuzzypid::supervisor::GainUpdate::Absolute
                                 : fuzzypid::supervisor::GainUpdate::Incremental;
  c.gain_max = {12.0, 0.06, 15.0};
  return c;
}

Controller make_controller() {
  std::array<Fuzzy, 6> joints;
  for (std::size_t i = 0; i < 6; ++i)
    joints[i] = Fuzzy(&fuzzypid::paper::kSystem<double>, config(i));
  return Controller(joints);
}

// Everything a joint must keep, whatever it was fed.
void expect_sane(const Fuzzy& joint, std::size_t i, std::uint64_t tick) {
  const auto c = config(i);
  const auto& g = joint.gains();
  ASSERT_TRUE(std::isfinite(joint.output())) << "joint " << i << " tick " << tick;
  ASSERT_LE(std::fabs(joint.output()), kOutputLimit) << "joint " << i << " tick " << tick;
  ASSERT_LE(std::fabs(joint.pid().integral()), kIntegralLimit) << "joint " << i << " tick " << tick;
  ASSERT_TRUE(g.finite());
  ASSERT_GE(g.kp, c.gain_min.kp);
  ASSERT_LE(g.kp, c.gain_max.kp);
  ASSERT_GE(g.ki, c.gain_min.ki);
  ASSERT_LE(g.ki, c.gain_max.ki);
  ASSERT_GE(g.kd, c.gain_min.kd);
  ASSERT_LE(g.kd, c.gain_max.kd);
}

TEST(Robustness, JitteredAndInvalidTimeStepsNaNMeasurementsAndSetpointJumpsKeepEveryInvariant) {
  const std::uint64_t seed = 20240607;
  std::mt19937_64 rng(seed);
  SCOPED_TRACE(::testing::Message() << "seed " << seed);

  Controller controller = make_controller();
  Vector position{}, velocity{}, setpoint{}, zero{};
  std::uint64_t nonfinite_injected = 0, bad_dt_injected = 0, faults = 0;

  for (std::uint64_t tick = 0; tick < 200'000; ++tick) {
    if (uniform(rng) < 1.0 / 300) {  // setpoint jump of up to +/-3 rad on every joint
      for (double& s : setpoint)
        s = 6.0 * uniform(rng) - 3.0;
    }
    Vector q = position;
    Vector qd = velocity;
    std::size_t bad_joint = 6;
    double injected = 0.0;
    if (uniform(rng) < 0.01) {
      bad_joint = static_cast<std::size_t>(rng() % 6);
      const std::uint64_t kind = rng() % 4;
      injected = kind == 0 ? kNaN : kind == 1 ? kInf : kind == 2 ? -kInf : 1e300;
      (uniform(rng) < 0.5 ? q : qd)[bad_joint] = injected;
    }
    const double dt = 0.05 * (0.5 + uniform(rng));  // +/-50 % jitter
    double dt_controller = dt;
    const bool bad_dt = uniform(rng) < 0.005;
    if (bad_dt) {
      const std::uint64_t kind = rng() % 4;
      dt_controller = kind == 0 ? 0.0 : kind == 1 ? -dt : kind == 2 ? kNaN : kInf;
      ++bad_dt_injected;
    }

    Controller::Input in;
    in.desired_position_rad = setpoint;
    in.desired_velocity_rad_s = zero;
    in.measured_position_rad = q;
    in.measured_velocity_rad_s = qd;
    const auto command = controller.step(in, dt_controller);

    for (std::size_t i = 0; i < 6; ++i) {
      const Status s = command.joint_status[i];
      if (fuzzypid::is_fault(s)) ++faults;
      if (bad_dt) {
        ASSERT_EQ(s, Status::InvalidTimeStep) << "tick " << tick;
      } else if (i == bad_joint && !std::isfinite(injected)) {
        ASSERT_EQ(s, Status::NonFiniteInput) << "tick " << tick;
      } else if (i != bad_joint) {
        ASSERT_FALSE(fuzzypid::is_fault(s)) << "tick " << tick << " joint " << i;
      }
      ASSERT_EQ(command.output[i], controller.joint(i).output());
      expect_sane(controller.joint(i), i, tick);
      // Unit double integrator, exact over dt with the command held.
      position[i] += velocity[i] * dt + 0.5 * command.output[i] * dt * dt;
      velocity[i] += command.output[i] * dt;
    }
    if (!bad_dt && bad_joint < 6 && !std::isfinite(injected)) ++nonfinite_injected;
  }
  EXPECT_GT(nonfinite_injected, 0u);
  EXPECT_GT(bad_dt_injected, 0u);
  EXPECT_GE(faults, nonfinite_injected + 6 * bad_dt_injected);
  // After all that, the loop still tracks: hold the last setpoint with clean input for 60 s.
  for (int tick = 0; tick < 1200; ++tick) {
    Controller::Input in;
    in.desired_position_rad = setpoint;
    in.measured_position_rad = position;
    in.measured_velocity_rad_s = velocity;
    const auto command = controller.step(in, 0.05);
    ASSERT_FALSE(fuzzypid::is_fault(command.status));
    for (std::size_t i = 0; i < 6; ++i) {
      position[i] += velocity[i] * 0.05 + 0.5 * command.output[i] * 0.0025;
      velocity[i] += command.output[i] * 0.05;
    }
  }
  for (std::size_t i = 0; i < 6; i += 2)  // the absolute-update joints settle
    EXPECT_NEAR(position[i], setpoint[i], 0.05) << "joint " << i;
}

TEST(Robustness, LongSaturationKeepsTheIntegralBoundedAndReleasesAtOnce) {
  Fuzzy joint(&fuzzypid::paper::kSystem<double>, config(0));
  fuzzypid::pid::Input<double> in;
  in.setpoint = 100.0;  // unreachable: the output saturates for the whole hour
  for (int tick = 0; tick < 72'000; ++tick) {
    ASSERT_FALSE(fuzzypid::is_fault(joint.update(in, 0.05)));
    ASSERT_EQ(joint.output(), kOutputLimit);
    ASSERT_LE(std::fabs(joint.pid().integral()), kIntegralLimit);
  }
  EXPECT_TRUE(joint.pid().saturated());
  // Once the error reverses, the output leaves the limit on the very next tick.
  in.setpoint = -1.0;
  ASSERT_FALSE(fuzzypid::is_fault(joint.update(in, 0.05)));
  EXPECT_LT(joint.output(), kOutputLimit);
}

}  // namespace
