// A bandwidth scale per joint (ControllerSpec::bandwidth_scale, docs/tuning.md "Per-joint
// bandwidth"): joint i runs the file's loop s_i times faster. Specification: every gain joint i
// uses on every tick is the uniform controller's times (s², s³, s) -- for a fixed PID, a schedule
// and an incremental fuzzy PID with finite bounds alike --, its derivative filter is Tf / s, and the
// scale is read, written and refused as a controller file states it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "fuzzypid/controller/joint_controllers.hpp"
#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid_support/uniform_real.hpp"

namespace {

namespace controller = fuzzypid::controller;
namespace cf = fuzzypid::controller_file;

controller::ControllerSpec load(const std::string& name) {
  controller::ControllerSpec spec;
  fuzzypid::FileError err;
  EXPECT_TRUE(cf::load(std::string(FUZZYPID_SOURCE_DIR) + "/tests/sim/data/" + name, spec, err))
      << err.to_string();
  return spec;
}

bool close(double a, double b) {
  return std::fabs(a - b) <= 1e-12 * std::max({1.0, std::fabs(a), std::fabs(b)});
}

class BandwidthScale : public ::testing::TestWithParam<const char*> {};

TEST_P(BandwidthScale, EveryGainAJointUsesIsTheUniformControllersTimesSSquaredSCubedS) {
  const controller::ControllerSpec scaled = load(GetParam());
  ASSERT_NE(scaled.bandwidth_scale, controller::kUniformBandwidth);
  controller::ControllerSpec uniform = scaled;
  uniform.bandwidth_scale = controller::kUniformBandwidth;
  controller::Vector limit;
  limit.fill(std::numeric_limits<double>::infinity());
  std::string error;
  auto a = controller::JointControllers::create(scaled, limit, error);
  ASSERT_TRUE(a) << error;
  auto b = controller::JointControllers::create(uniform, limit, error);
  ASSERT_TRUE(b) << error;
  std::mt19937_64 rng(20261207);
  fuzzypid::support::UniformReal<double> u(-0.3, 0.3);
  int moved = 0;  // ticks on which some gain differs from K0 (the supervisor acted)
  for (int tick = 0; tick < 600; ++tick) {
    controller::Input in;
    for (std::size_t j = 0; j < controller::kJoints; ++j) {
      in.desired_position_rad[j] = u(rng);
      in.measured_position_rad[j] = u(rng);
      in.desired_velocity_rad_s[j] = 3 * u(rng);
      in.measured_velocity_rad_s[j] = 3 * u(rng);
    }
    (void)a->step(in, scaled.units.tick_s);
    (void)b->step(in, scaled.units.tick_s);
    for (std::size_t j = 0; j < controller::kJoints; ++j) {
      const double s = scaled.bandwidth_scale[j];
      const fuzzypid::pid::Gains<double> ga = a->gains(j), gb = b->gains(j);
      ASSERT_TRUE(close(ga.kp, s * s * gb.kp)) << "tick " << tick << " joint " << j;
      ASSERT_TRUE(close(ga.ki, s * s * s * gb.ki)) << "tick " << tick << " joint " << j;
      ASSERT_TRUE(close(ga.kd, s * gb.kd)) << "tick " << tick << " joint " << j;
      const fuzzypid::pid::Gains<double> k0 = controller::pid_config(uniform, j, 1.0).gains;
      moved += gb.kp != k0.kp || gb.ki != k0.ki || gb.kd != k0.kd ? 1 : 0;
    }
  }
  if (controller::family_traits(scaled.family).supervised()) {
    EXPECT_GT(moved, 1000);
  }
  for (std::size_t j = 0; j < controller::kJoints; ++j)
    EXPECT_TRUE(close(controller::pid_config(scaled, j, 1.0).derivative_filter_s,
                      scaled.pid.derivative_filter_s / scaled.bandwidth_scale[j]));
}

TEST_P(BandwidthScale, AControllerFileWritesAndReadsItUnchanged) {
  const controller::ControllerSpec spec = load(GetParam());
  cf::ControllerFile file;
  file.controller = spec;
  const std::string text = cf::to_toml(file);
  EXPECT_NE(text.find("bandwidth_scale = ["), std::string::npos);
  controller::ControllerSpec back;
  fuzzypid::FileError err;
  ASSERT_TRUE(cf::parse(text, "written", back, err)) << err.to_string();
  EXPECT_EQ(back.bandwidth_scale, spec.bandwidth_scale);
}

INSTANTIATE_TEST_SUITE_P(Families, BandwidthScale,
                         ::testing::Values("per_joint_pid.toml", "per_joint_scheduled.toml",
                                           "per_joint_fuzzy.toml"));

TEST(BandwidthScaleFile, AUniformControllerWritesNoScale) {
  cf::ControllerFile file;
  file.controller = controller::paper_pid();
  EXPECT_EQ(cf::to_toml(file).find("bandwidth_scale"), std::string::npos);
}

TEST(BandwidthScaleFile, ScalesOutOfRangeOrMiscountedAreRefusedWithLineAndColumn) {
  const std::string head =
      "family = \"pid\"\n[units]\ngains = \"acceleration\"\nform = \"per-tick\"\n"
      "tick_s = 0.05\n[gains]\nkp = 1.0\nki = 0.0\nkd = 1.0\n";
  const struct {
    const char* line;
    const char* message;
  } cases[] = {
      {"bandwidth_scale = [1.0, 1.0, 1.0, 1.0, 1.0]", "bandwidth_scale must have 6 numbers"},
      {"bandwidth_scale = [1.0, 1.0, 1.0, 1.0, 1.0, 0.0]", "bandwidth_scale[5] must be within"},
      {"bandwidth_scale = [1.0, 1.0, 1.0, 1.0, 1.0, 2000.0]", "bandwidth_scale[5] must be within"},
      {"bandwidth_scale = [1.0, nan, 1.0, 1.0, 1.0, 1.0]", "bandwidth_scale[1]"},
      {"bandwidth_scale = [1.0, \"2\", 1.0, 1.0, 1.0, 1.0]", "bandwidth_scale[1]"},
      {"bandwidth_scale = 2.0", "bandwidth_scale"},
  };
  for (const auto& c : cases) {
    controller::ControllerSpec spec;
    fuzzypid::FileError err;
    EXPECT_FALSE(cf::parse(head + c.line + "\n", "bad.toml", spec, err)) << c.line;
    EXPECT_NE(err.to_string().find(c.message), std::string::npos) << err.to_string();
    EXPECT_EQ(err.line, 10) << c.line;
  }
}

TEST(BandwidthScaleSpec, ValidateRefusesAScaleOutsideItsRange) {
  controller::ControllerSpec spec = controller::paper_pid();
  for (const double bad :
       {0.0, -1.0, 1e-4, 1e4, std::nan(""), std::numeric_limits<double>::infinity()}) {
    spec.bandwidth_scale[3] = bad;
    EXPECT_NE(controller::validate(spec).find("bandwidth_scale"), std::string::npos) << bad;
  }
  spec.bandwidth_scale[3] = 1e-3;
  EXPECT_EQ(controller::validate(spec), "");
}

}  // namespace
