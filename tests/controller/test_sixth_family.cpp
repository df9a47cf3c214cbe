// A sixth controller family, added in this test build by its two files alone
// (sixth_family/p_schedule.hpp and its supervisor sixth_family/proportional_ramp.hpp; the build
// names them through FUZZYPID_EXTRA_FAMILY_HEADER and FUZZYPID_EXTRA_FAMILY): the library's
// controller, controller-file, header-export and tuner code, compiled into this program with the
// longer list, read, check, build, run, write and search it without naming it.
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "fuzzypid/codegen/export_header.hpp"
#include "fuzzypid/controller/families.hpp"
#include "fuzzypid/controller/joint_controllers.hpp"
#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid/tune/parameters.hpp"

namespace {

namespace controller = fuzzypid::controller;
namespace cf = fuzzypid::controller_file;

constexpr const char* kFile = R"(family = "p-schedule"
[units]
gains = "acceleration"
form = "per-tick"
tick_s = 0.05
[gains]
kp = 4.0
ki = 0.001
kd = 100.0
[supervisor]
error_scale = 10.0
error_rate_scale = 1.0
output_scale = [3.0, 1.0, 1.0]
)";

controller::ControllerSpec parsed(const std::string& text) {
  controller::ControllerSpec spec;
  fuzzypid::FileError error;
  EXPECT_TRUE(cf::parse(text, "p_schedule.toml", spec, error)) << error.to_string();
  return spec;
}

TEST(SixthFamily, IsInTheListWithItsNameAndTraits) {
  ASSERT_EQ(controller::kFamilies.size(), 5u);
  const std::optional<controller::Family> f = controller::parse_family("p-schedule");
  ASSERT_TRUE(f.has_value());
  EXPECT_EQ(f->index(), 4u);
  EXPECT_STREQ(controller::to_string(*f), "p-schedule");
  EXPECT_TRUE(controller::family_traits(*f).supervised());
  EXPECT_EQ(controller::family_traits(*f).output_scale, controller::OutputScale::Ratios);
  EXPECT_NE(fuzzypid::names_of(controller::kFamilyNames).find("|p-schedule"), std::string::npos);
}

TEST(SixthFamily, AControllerFileReadsAndWritesItUnchanged) {
  const controller::ControllerSpec spec = parsed(kFile);
  EXPECT_EQ(spec.family, *controller::parse_family("p-schedule"));
  EXPECT_EQ(spec.supervisor.output_scale[0], 3.0);
  const std::string text = cf::to_toml(spec);
  EXPECT_NE(text.find("family = \"p-schedule\""), std::string::npos);
  EXPECT_NE(text.find("large-error gain ratios"), std::string::npos);
  EXPECT_EQ(cf::to_toml(parsed(text)), text);
}

TEST(SixthFamily, ItsOwnCheckRefusesRatiosItWouldIgnore) {
  std::string text = kFile;
  text.replace(text.find("[3.0, 1.0, 1.0]"), 15, "[3.0, 2.0, 1.0]");
  controller::ControllerSpec spec;
  fuzzypid::FileError error;
  EXPECT_FALSE(cf::parse(text, "p_schedule.toml", spec, error));
  EXPECT_NE(error.to_string().find("schedules Kp only"), std::string::npos) << error.to_string();
  // The traits' generic checks apply too: ratios are > 0.
  text = kFile;
  text.replace(text.find("[3.0, 1.0, 1.0]"), 15, "[0.0, 1.0, 1.0]");
  EXPECT_FALSE(cf::parse(text, "p_schedule.toml", spec, error));
  EXPECT_NE(error.to_string().find("p-schedule family's output_scale"), std::string::npos)
      << error.to_string();
}

TEST(SixthFamily, ItsJointsScheduleKpAndKeepKiAndKd) {
  const controller::ControllerSpec spec = parsed(kFile);
  controller::Vector limit;
  limit.fill(1e6);
  std::string error;
  auto joints = controller::JointControllers::create(spec, limit, error);
  ASSERT_TRUE(joints.has_value()) << error;
  const fuzzypid::pid::Gains<double> k0 =
      controller::to_continuous(spec.gains, spec.units.form, 0.05);
  for (const double e : {0.0, 0.02, 0.05, 0.5}) {
    controller::Input in{};
    in.desired_position_rad.fill(e);
    const controller::Command out = joints->step(in, 0.05);
    ASSERT_EQ(out.status, fuzzypid::Status::Ok);
    // w = min(1, Ke |e| + Kec |ec|) with ec = 0 (both rates zero): Kp = K0p (1 + (Rp - 1) w).
    const double w = std::min(1.0, 10.0 * e);
    for (std::size_t i = 0; i < controller::kJoints; ++i) {
      const fuzzypid::pid::Gains<double> k = joints->gains(i);
      EXPECT_DOUBLE_EQ(k.kp, k0.kp * (1.0 + 2.0 * w)) << "e = " << e;
      EXPECT_EQ(k.ki, k0.ki);
      EXPECT_EQ(k.kd, k0.kd);
    }
  }
}

TEST(SixthFamily, TheHeaderExportWritesItsSupervisor) {
  const std::string h = fuzzypid::codegen::export_header(parsed(kFile), "p_schedule", "test");
  EXPECT_NE(h.find("kFamily = \"p-schedule\""), std::string::npos);
  EXPECT_NE(h.find("using Supervisor = fuzzypid_test::ProportionalRamp<Scalar>;"),
            std::string::npos);
  EXPECT_NE(h.find("#include \"proportional_ramp.hpp\""), std::string::npos);
  EXPECT_NE(h.find("fuzzypid::supervisor::FuzzyPid<Scalar, Supervisor<Scalar>, "
                   "fuzzypid::pid::ObserverStorage::Omitted>"),
            std::string::npos);
}

TEST(SixthFamily, TheTunerSearchesItsEightParameters) {
  const controller::Family f = *controller::parse_family("p-schedule");
  const std::vector<fuzzypid::tune::SearchBox> box = fuzzypid::tune::default_box(f);
  ASSERT_EQ(box.size(), 8u);
  EXPECT_EQ(box[5].name, "rp");
  // A fixed PID becomes the family exactly (Rp = 1 moves nothing).
  controller::ControllerSpec converted;
  std::string error;
  ASSERT_TRUE(fuzzypid::tune::convert(controller::paper_pid(), f, converted, error)) << error;
  EXPECT_EQ(converted.family, f);
  EXPECT_EQ(controller::validate(converted), "");
}

}  // namespace
