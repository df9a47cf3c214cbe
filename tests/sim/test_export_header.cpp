// `fuzzypid export-header`: the generated headers (built from the shipped controller files by
// tests/sim/CMakeLists.txt) give controllers equal to the files' bit for bit on x86, and compile
// for float as well.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>

#include "fuzzypid/control/joint_controller.hpp"
#include "fuzzypid/controller/joint_controllers.hpp"
#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid/sim/random.hpp"
#include "paper_fuzzy.hpp"
#include "tuned_fuzzy.hpp"
#include "tuned_pid.hpp"
#include "tuned_scheduled.hpp"

namespace {

using namespace fuzzypid;
namespace cf = controller_file;
namespace ctl = controller;
constexpr std::size_t kJ = 6;

// Equal bit patterns (NaN payloads and the sign of zero included).
bool same_bits(double a, double b) {
  std::uint64_t x = 0, y = 0;
  std::memcpy(&x, &a, sizeof x);
  std::memcpy(&y, &b, sizeof y);
  return x == y;
}

// Steps the file's controller and the header's side by side on seeded random inputs (errors up to
// 0.2 rad, rates up to 1 rad/s) with output limit 3 rad/s²; every output must match bit for bit.
template <class Controller>
void expect_equal_to_file(const char* file, const Controller& prototype) {
  ctl::ControllerSpec spec;
  fuzzypid::FileError err;
  ASSERT_TRUE(cf::load(std::string(FUZZYPID_SOURCE_DIR "/controllers/") + file, spec, err))
      << err.to_string();
  std::string error;
  auto from_file = ctl::JointControllers::create(spec, ctl::Vector{3, 3, 3, 3, 3, 3}, error);
  ASSERT_TRUE(from_file) << error;
  control::JointController<double, kJ, Controller> from_header(prototype);
  sim::Random rng(2024);
  for (int k = 0; k < 400; ++k) {
    ctl::Input in;
    for (std::size_t i = 0; i < kJ; ++i) {
      in.desired_position_rad[i] = rng.uniform(-0.2, 0.2);
      in.desired_velocity_rad_s[i] = rng.uniform(-1.0, 1.0);
      in.measured_position_rad[i] = rng.uniform(-0.2, 0.2);
      in.measured_velocity_rad_s[i] = rng.uniform(-1.0, 1.0);
    }
    const auto a = from_file->step(in, spec.units.tick_s);
    const auto b = from_header.step(in, tuned_pid::kTickS);
    for (std::size_t i = 0; i < kJ; ++i) {
      ASSERT_TRUE(same_bits(a.torque_nm[i], b.torque_nm[i]))
          << file << " tick " << k << " joint " << i << ": " << a.torque_nm[i] << " vs "
          << b.torque_nm[i];
      ASSERT_EQ(a.joint_status[i], b.joint_status[i]);
    }
  }
}

TEST(ExportHeader, GeneratedControllersEqualTheFilesBitForBit) {
  expect_equal_to_file("tuned_pid.toml", tuned_pid::make_controller<double>(3.0));
  expect_equal_to_file("tuned_scheduled.toml", tuned_scheduled::make_controller<double>(3.0));
  expect_equal_to_file("tuned_fuzzy.toml", tuned_fuzzy::make_controller<double>(3.0));
  expect_equal_to_file("paper_fuzzy.toml", paper_fuzzy::make_controller<double>(3.0));
}

TEST(ExportHeader, GeneratedConfigurationIsConstexprAndInstantiatesForFloat) {
  constexpr auto c = tuned_fuzzy::config<float>(3.0f);
  static_assert(c.valid(), "the exported configuration is valid");
  auto joint = tuned_scheduled::make_controller<float>(3.0f);
  pid::Input<float> in;
  in.setpoint = 0.1f;
  EXPECT_EQ(joint.update(in, 0.05f), Status::Ok);
  EXPECT_GT(joint.output(), 0.0f);
  EXPECT_STREQ(tuned_fuzzy::kFamily, "fuzzy");
}

}  // namespace
