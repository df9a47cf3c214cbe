// The closed loop (fuzzypid/sim/closed_loop.hpp) and conditions: a controller file run through
// sim::Experiment equals the same controller built by hand, tick by tick and bit for bit; the tick
// allocates nothing; conditions change what they name.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "fuzzypid/control/fuzzy_pid.hpp"
#include "fuzzypid/control/gain_schedule.hpp"
#include "fuzzypid/control/joint_controller.hpp"
#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid/paper.hpp"
#include "fuzzypid/robot/path.hpp"
#include "fuzzypid/robot/plant.hpp"
#include "fuzzypid/robot/robot_model.hpp"
#include "fuzzypid/sim/closed_loop.hpp"
#include "fuzzypid/sim/experiment.hpp"
#include "fuzzypid/sim/random.hpp"
#include "fuzzypid_support/counting_new.hpp"

namespace {

using namespace fuzzypid;
namespace cf = controller_file;
constexpr std::size_t kJ = robot::kNumJoints;

// Equal bit patterns (NaN payloads and the sign of zero included).
bool same_bits(double a, double b) {
  std::uint64_t x = 0, y = 0;
  std::memcpy(&x, &a, sizeof x);
  std::memcpy(&y, &b, sizeof y);
  return x == y;
}

class ClosedLoopTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto loaded = robot::RobotModel::load(robot::default_urdf_path());
    ASSERT_TRUE(loaded.model) << loaded.error;
    model_ = std::move(loaded.model);
    std::string error;
    experiment_ = sim::Experiment::create(*model_, robot::paper_path_spec(), {}, error);
    ASSERT_TRUE(experiment_) << error;
  }
  std::optional<robot::RobotModel> model_;
  std::optional<sim::Experiment> experiment_;
};

// The same loop written out by hand: plant, noise, six FuzzyPid<GainSchedule> configured with the
// file's numbers converted by hand (Ki / dt, Kd dt; scheduled scales K0 (R - 1)).
TEST_F(ClosedLoopTest, ControllerFileThroughTheExperimentEqualsAHandBuiltLoopBitForBit) {
  const std::string path = FUZZYPID_SOURCE_DIR "/tests/sim/data/hand_scheduled.toml";
  cf::ControllerSpec spec;
  cf::Error err;
  ASSERT_TRUE(cf::load(path, spec, err)) << err.to_string();

  sim::Condition cond;
  cond.name = "hand";
  cond.payload_scale = 1.3;
  cond.friction_per_s = 0.5;
  cond.contact_rad_s2 = 0.2;
  cond.noise_position_rad = 1e-4;
  cond.noise_velocity_rad_s = 1e-3;
  cond.seed = 99;
  cond.initial_error_rad = -0.04;
  const sim::RunResult r = experiment_->run(cond, spec);
  ASSERT_TRUE(r.ok) << r.error;

  // By hand. The file: kp 150, ki 0.004, kd 300 per tick at 0.05 s; ke 20, kec 2; R 0.5, 2, 0.8.
  const double dt = 0.05;
  const auto& J = experiment_->nominal_inertia();
  const robot::JointVector limit = model_->effort_limits_nm();
  using Joint = control::FuzzyPid<double, control::GainSchedule<double>>;
  const control::GainSchedule<double> schedule;
  std::vector<Joint> built;
  for (std::size_t i = 0; i < kJ; ++i) {
    control::FuzzyPidConfig<double> c;
    c.pid.gains = {150.0, 0.004 / dt, 300.0 * dt};
    c.pid.output_min = -limit[i] / J[i];
    c.pid.output_max = limit[i] / J[i];
    c.error_scale = 20.0;
    c.error_rate_scale = 2.0;
    c.output_scale = {150.0 * (0.5 - 1.0), (0.004 / dt) * (2.0 - 1.0), (300.0 * dt) * (0.8 - 1.0)};
    built.emplace_back(&schedule, c);
  }
  const std::array<Joint, kJ> joints = {built[0], built[1], built[2], built[3], built[4], built[5]};
  control::JointController<double, kJ, control::FuzzyPid<double, control::GainSchedule<double>>>
      controller(joints);
  robot::PlantConfig pc;
  pc.inertia_scale.fill(1.3);
  for (std::size_t i = 0; i < kJ; ++i)
    pc.damping_nms[i] = 0.5 * J[i];
  pc.torque_limit_nm = limit;
  robot::JointPlant plant(*model_, pc);
  const auto& p = experiment_->path();
  robot::JointVector q0 = p.position_rad.front();
  for (double& q : q0)
    q += 0.04;
  plant.reset(q0, {});
  sim::Random noise(99);
  const sim::PulseTrain pulses = sim::contact_pulses(0.2);
  ASSERT_EQ(r.rows.size(), p.time_s.size() * kJ);
  for (std::size_t k = 0; k < p.time_s.size(); ++k) {
    robot::JointVector qm = plant.position(), vm = plant.velocity();
    for (std::size_t i = 0; i < kJ; ++i) {
      qm[i] += noise.normal(1e-4);
      vm[i] += noise.normal(1e-3);
    }
    for (std::size_t i = 0; i < kJ; ++i) {
      const auto& row = r.rows[k * kJ + i];
      ASSERT_TRUE(same_bits(row.theta, plant.position()[i])) << "tick " << k << " joint " << i;
    }
    control::JointInput<double, kJ> in;
    in.desired_position_rad = p.position_rad[k];
    in.desired_velocity_rad_s = p.velocity_rad_s[k];
    in.measured_position_rad = qm;
    in.measured_velocity_rad_s = vm;
    const auto cmd = controller.step(in, dt);
    robot::JointVector torque{}, dist{};
    for (std::size_t i = 0; i < kJ; ++i) {
      ASSERT_TRUE(same_bits(r.rows[k * kJ + i].u, cmd.torque_nm[i])) << "tick " << k;
      torque[i] = J[i] * cmd.torque_nm[i];
      dist[i] = pulses.at(p.time_s[k]) * J[i];
    }
    if (k + 1 < p.time_s.size()) (void)plant.step(torque, p.time_s[k + 1] - p.time_s[k], dist);
  }
}

// A rule file (rulebases/paper.fll, the paper's tables as a fuzzylite file) in place of the
// built-in tables: the same controller up to rounding (the engine and the table system agree within
// 3e-16).
TEST_F(ClosedLoopTest, ARuleFileRunsLikeTheBuiltInTablesItEncodes) {
  cf::ControllerSpec from_file;
  cf::Error err;
  ASSERT_TRUE(cf::load(FUZZYPID_SOURCE_DIR "/tests/sim/data/engine_fuzzy.toml", from_file, err))
      << err.to_string();
  ASSERT_NE(from_file.supervisor.rule_model, nullptr);
  sim::Condition cond;
  cond.initial_error_rad = -0.03;
  const auto a = experiment_->run(cond, from_file);
  const auto b = experiment_->run(cond, cf::paper_fuzzy());
  ASSERT_TRUE(a.ok) << a.error;
  ASSERT_TRUE(b.ok) << b.error;
  ASSERT_EQ(a.rows.size(), b.rows.size());
  bool gains_moved = false;
  for (std::size_t k = 0; k < a.rows.size(); ++k) {
    EXPECT_NEAR(a.rows[k].theta, b.rows[k].theta, 1e-12) << k;
    EXPECT_NEAR(a.rows[k].kp, b.rows[k].kp, 1e-12) << k;
    gains_moved = gains_moved || a.rows[k].kp != 4.0;
  }
  EXPECT_TRUE(gains_moved);
}

TEST_F(ClosedLoopTest, ATickAllocatesNothing) {
  for (const cf::ControllerSpec& spec : {cf::paper_pid(), cf::paper_fuzzy()}) {
    sim::Condition cond;
    cond.noise_position_rad = 1e-4;
    cond.contact_rad_s2 = 0.5;
    std::string error;
    auto loop = sim::ClosedLoop::create(*experiment_, cond, spec, error);
    ASSERT_TRUE(loop) << error;
    const auto before = support::allocation_count();
    for (std::size_t k = 0; k < loop->samples(); ++k)
      (void)loop->tick(k);
    EXPECT_EQ(support::allocation_count(), before);
  }
}

TEST_F(ClosedLoopTest, NegativeInitialErrorStartsAheadAndReverseRunsBToA) {
  sim::Condition ahead;
  ahead.initial_error_rad = -0.05;
  const auto r = experiment_->run(ahead, cf::paper_pid());
  ASSERT_TRUE(r.ok) << r.error;
  for (std::size_t i = 0; i < kJ; ++i)
    EXPECT_NEAR(r.rows[i].error, -0.05, 1e-15);  // theta_d - (theta_d + 0.05)
  sim::Condition back;
  back.reverse = true;
  const auto b = experiment_->run(back, cf::paper_pid());
  ASSERT_TRUE(b.ok) << b.error;
  const auto& fwd = experiment_->path().position_rad;
  for (std::size_t i = 0; i < kJ; ++i) {
    EXPECT_NEAR(b.rows[i].theta_d, fwd.back()[i], 1e-9);
    EXPECT_NEAR(b.rows[b.rows.size() - kJ + i].theta_d, fwd.front()[i], 1e-9);
  }
}

TEST_F(ClosedLoopTest, InvalidConditionsAreRefused) {
  sim::Condition bad;
  bad.payload_scale = 0.0;
  const auto r = experiment_->run(bad, cf::paper_pid());
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("payload"), std::string::npos);
}

TEST(Random, IsTheSameSequenceForTheSameSeedAndStandardNormalOnAverage) {
  sim::Random a(5), b(5);
  double sum = 0.0, sum_sq = 0.0;
  constexpr int n = 20000;
  for (int k = 0; k < n; ++k) {
    const double x = a.normal(1.0);
    EXPECT_EQ(x, b.normal(1.0));
    sum += x;
    sum_sq += x * x;
  }
  EXPECT_NEAR(sum / n, 0.0, 0.03);  // 4 standard errors
  EXPECT_NEAR(sum_sq / n, 1.0, 0.04);
  EXPECT_EQ(a.normal(0.0), 0.0);
}

TEST(GainSchedule, IsARampInAbsEPlusAbsEcSaturatingAtOne) {
  const control::GainSchedule<double> s;
  auto ws = s.make_workspace();
  std::array<double, 3> d{};
  EXPECT_EQ(s.infer(0.0, 0.0, ws, d), Status::Ok);
  EXPECT_EQ(d[0], 0.0);
  EXPECT_EQ(s.infer(-0.25, 0.5, ws, d), Status::Ok);
  EXPECT_EQ(d[0], 0.75);
  EXPECT_EQ(d[1], 0.75);
  EXPECT_EQ(d[2], 0.75);
  EXPECT_EQ(s.infer(2.0, -3.0, ws, d), Status::Ok);
  EXPECT_EQ(d[1], 1.0);
  EXPECT_EQ(s.infer(std::nan(""), 0.0, ws, d), Status::NonFiniteInput);
  EXPECT_EQ(d[0], 0.0);
}

}  // namespace
