// The closed loop (fuzzypid/sim/closed_loop.hpp) and conditions: a controller file run through
// sim::Experiment equals the same controller built by hand, tick by tick and bit for bit; the tick
// allocates nothing; each kind of injected fault does what it names, on its joint only, and a
// default injection nothing; conditions change what they name.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "fuzzypid/controller/joint_controllers.hpp"
#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid/paper.hpp"
#include "fuzzypid/robot/path.hpp"
#include "fuzzypid/robot/plant.hpp"
#include "fuzzypid/robot/robot_model.hpp"
#include "fuzzypid/sim/closed_loop.hpp"
#include "fuzzypid/sim/experiment.hpp"
#include "fuzzypid/sim/metrics.hpp"
#include "fuzzypid/sim/random.hpp"
#include "fuzzypid/supervisor/fuzzy_pid.hpp"
#include "fuzzypid/supervisor/gain_schedule.hpp"
#include "fuzzypid/supervisor/joint_controller.hpp"
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
    sim::ExperimentOptions options;
    options.plant.armature_kgm2 = robot::kEr50ArmatureKgm2;  // the bundled ER50-C20's motors
    experiment_ = sim::Experiment::create(*model_, robot::paper_path_spec(), options, error);
    ASSERT_TRUE(experiment_) << error;
  }
  std::optional<robot::RobotModel> model_;
  std::optional<sim::Experiment> experiment_;
};

// The same loop written out by hand: plant, noise, six FuzzyPid<GainSchedule> configured with the
// file's numbers converted by hand (Ki / dt, Kd dt; scheduled scales K0 (R - 1)).
TEST_F(ClosedLoopTest, ControllerFileThroughTheExperimentEqualsAHandBuiltLoopBitForBit) {
  const std::string path = FUZZYPID_SOURCE_DIR "/tests/sim/data/hand_scheduled.toml";
  controller::ControllerSpec spec;
  fuzzypid::FileError err;
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
  using Joint = supervisor::FuzzyPid<double, supervisor::GainSchedule<double>>;
  const supervisor::GainSchedule<double> schedule;
  std::vector<Joint> built;
  for (std::size_t i = 0; i < kJ; ++i) {
    supervisor::FuzzyPidConfig<double> c;
    c.pid.gains = {150.0, 0.004 / dt, 300.0 * dt};
    c.pid.output_min = -limit[i] / J[i];
    c.pid.output_max = limit[i] / J[i];
    c.error_scale = 20.0;
    c.error_rate_scale = 2.0;
    c.output_scale = {150.0 * (0.5 - 1.0), (0.004 / dt) * (2.0 - 1.0), (300.0 * dt) * (0.8 - 1.0)};
    built.emplace_back(&schedule, c);
  }
  const std::array<Joint, kJ> joints = {built[0], built[1], built[2], built[3], built[4], built[5]};
  supervisor::JointController<double, kJ,
                              supervisor::FuzzyPid<double, supervisor::GainSchedule<double>>>
      controller(joints);
  robot::PlantConfig pc;
  pc.armature_kgm2 = robot::kEr50ArmatureKgm2;  // as the experiment gives the bundled ER50-C20
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
    supervisor::JointInput<double, kJ> in;
    in.desired_position_rad = p.position_rad[k];
    in.desired_velocity_rad_s = p.velocity_rad_s[k];
    in.measured_position_rad = qm;
    in.measured_velocity_rad_s = vm;
    const auto cmd = controller.step(in, dt);
    robot::JointVector torque{}, dist{};
    for (std::size_t i = 0; i < kJ; ++i) {
      ASSERT_TRUE(same_bits(r.rows[k * kJ + i].u, cmd.output[i])) << "tick " << k;
      torque[i] = J[i] * cmd.output[i];
      dist[i] = pulses.at(p.time_s[k]) * J[i];
    }
    if (k + 1 < p.time_s.size()) (void)plant.step(torque, p.time_s[k + 1] - p.time_s[k], dist);
  }
}

// A rule file (rulebases/paper.fll, the paper's tables as a fuzzylite file) in place of the
// built-in tables: the same controller up to rounding (the engine and the table system agree within
// 3e-16).
TEST_F(ClosedLoopTest, ARuleFileRunsLikeTheBuiltInTablesItEncodes) {
  controller::ControllerSpec from_file;
  fuzzypid::FileError err;
  ASSERT_TRUE(cf::load(FUZZYPID_SOURCE_DIR "/tests/sim/data/engine_fuzzy.toml", from_file, err))
      << err.to_string();
  ASSERT_NE(from_file.supervisor.rule_model, nullptr);
  sim::Condition cond;
  cond.initial_error_rad = -0.03;
  const auto a = experiment_->run(cond, from_file);
  const auto b = experiment_->run(cond, controller::paper_fuzzy());
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
  controller::ControllerSpec observed = controller::paper_pid();
  observed.pid.derivative = pid::DerivativeSource::Observer;
  observed.pid.observer_bandwidth_hz = 1.0;
  for (const controller::ControllerSpec& spec :
       {controller::paper_pid(), controller::paper_fuzzy(), observed}) {
    sim::Condition cond;
    cond.noise_position_rad = 1e-4;
    cond.contact_rad_s2 = 0.5;
    std::string error;
    auto loop = sim::ClosedLoop::create(*experiment_, cond, spec, error);
    ASSERT_TRUE(loop) << error;
    const auto before = support::allocation_count();
    for (std::size_t k = 0; k < loop->samples(); ++k)
      (void)loop->tick(k);
    // Every injection, the cyclic path and a plant reset.
    sim::TickInjection injection;
    injection.reference_offset_rad.fill(0.1);
    injection.measured_position_offset_rad.fill(1e-3);
    injection.measured_velocity_rad_s[2] = std::numeric_limits<double>::quiet_NaN();
    injection.controller_dt_s = 0.045;
    injection.plant_dt_s = 0.055;
    injection.disturbance_torque_nm.fill(1.0);
    for (std::uint64_t t = 0; t < 3 * loop->samples(); ++t)
      (void)loop->tick(loop->cyclic_sample(t), injection);
    loop->reset_plant(experiment_->path().position_rad.front(), robot::JointVector{});
    EXPECT_EQ(support::allocation_count(), before);
  }
}

// Another arm on a path file with a continuous joint, coupled dynamics with gravity, a payload
// mass and gravity feed-forward: still no allocation per tick.
TEST(ClosedLoopAnyRobot, ATickAllocatesNothingWithCoupledGravityPayloadAndFeedForward) {
  sim::RobotSetup setup;
  setup.urdf = FUZZYPID_SOURCE_DIR "/tests/robot/data/continuous_wrist.urdf";
  setup.path = FUZZYPID_SOURCE_DIR "/paths/ur5_deburring_contour.csv";
  setup.tick_s = 0.01;
  setup.armature_kgm2 = robot::JointVector{0.4, 0.4, 0.4, 0.1, 0.1, 0.1};
  setup.ik_seed_rad = robot::JointVector{0.0, -1.3, 1.6, -0.9, -1.2, 0.3};
  std::string error;
  const auto ex = sim::Experiment::create(setup, sim::ExperimentOptions{}, error);
  ASSERT_TRUE(ex) << error;
  sim::Condition cond;
  cond.robot = setup;
  cond.payload_kg = 2.0;
  cond.dynamics = robot::PlantCoupling::Coupled;
  cond.gravity = true;
  controller::ControllerSpec spec = controller::paper_fuzzy();
  spec.feedforward.gravity = true;
  auto loop = sim::ClosedLoop::create(*ex, cond, spec, error);
  ASSERT_TRUE(loop) << error;
  const auto before = support::allocation_count();
  for (std::size_t k = 0; k < loop->samples(); ++k)
    (void)loop->tick(k, k + 1 < loop->samples());
  EXPECT_EQ(support::allocation_count(), before);
}

// Gravity feed-forward adds g(theta_d), the model's gravity torque at the desired angles, to the
// controller's torque: one tick with the arm 0.3 rad off the path on joints 2 and 3, with and
// without it, differs by exactly that (g at the measured angles differs by tens of N m).
TEST_F(ClosedLoopTest, GravityFeedForwardIsTheModelsGravityAtTheDesiredAngles) {
  controller::ControllerSpec with_ff = controller::paper_pid();
  with_ff.feedforward.gravity = true;
  std::string error;
  auto plain =
      sim::ClosedLoop::create(*experiment_, sim::Condition{}, controller::paper_pid(), error);
  auto fed = sim::ClosedLoop::create(*experiment_, sim::Condition{}, with_ff, error);
  ASSERT_TRUE(plain && fed) << error;
  robot::JointVector off = experiment_->path().position_rad.front();
  off[1] += 0.3;
  off[2] -= 0.3;
  plain->reset_plant(off, robot::JointVector{});
  fed->reset_plant(off, robot::JointVector{});
  const sim::TickResult a = plain->tick(0, false);
  const sim::TickResult b = fed->tick(0, false);
  EXPECT_EQ(b.theta, off);
  const robot::JointVector g_desired = model_->gravity_torque(b.theta_d);
  const robot::JointVector g_measured = model_->gravity_torque(b.theta);
  double apart = 0.0;
  for (std::size_t i = 0; i < kJ; ++i) {
    EXPECT_TRUE(same_bits(a.command.output[i], b.command.output[i])) << i;
    EXPECT_NEAR(b.torque_nm[i] - a.torque_nm[i], g_desired[i], 1e-9 * (1 + std::fabs(g_desired[i])))
        << "joint " << i;
    apart = std::fmax(apart, std::fabs(g_desired[i] - g_measured[i]));
  }
  EXPECT_GT(apart, 10.0) << "the offset must move g";
}

// Fault injection (sim::TickInjection), reset_plant and the cyclic path.

// Every value of two tick results has the same bits.
void expect_same_tick(const sim::TickResult& a, const sim::TickResult& b, std::size_t k) {
  EXPECT_TRUE(same_bits(a.t_s, b.t_s)) << "tick " << k;
  EXPECT_EQ(a.plant, b.plant) << "tick " << k;
  EXPECT_EQ(a.command.status, b.command.status) << "tick " << k;
  for (std::size_t i = 0; i < kJ; ++i) {
    EXPECT_TRUE(same_bits(a.theta_d[i], b.theta_d[i])) << "tick " << k << " joint " << i;
    EXPECT_TRUE(same_bits(a.theta_d_dot[i], b.theta_d_dot[i])) << "tick " << k << " joint " << i;
    EXPECT_TRUE(same_bits(a.theta[i], b.theta[i])) << "tick " << k << " joint " << i;
    EXPECT_TRUE(same_bits(a.theta_dot[i], b.theta_dot[i])) << "tick " << k << " joint " << i;
    EXPECT_TRUE(same_bits(a.command.output[i], b.command.output[i]))
        << "tick " << k << " joint " << i;
    EXPECT_EQ(a.command.joint_status[i], b.command.joint_status[i]) << "tick " << k;
    EXPECT_TRUE(same_bits(a.torque_nm[i], b.torque_nm[i])) << "tick " << k << " joint " << i;
  }
}

// Noise, contact pulses and an initial error, so that every injected path carries a value.
sim::Condition busy_condition() {
  sim::Condition cond;
  cond.name = "busy";
  cond.noise_position_rad = 1e-4;
  cond.noise_velocity_rad_s = 1e-3;
  cond.contact_rad_s2 = 0.5;
  cond.seed = 3;
  cond.initial_error_rad = 0.04;
  return cond;
}

TEST_F(ClosedLoopTest, ADefaultInjectionTicksBitForBitLikeThePlainTick) {
  for (const controller::ControllerSpec& spec :
       {controller::paper_pid(), controller::paper_fuzzy()}) {
    std::string error;
    auto plain = sim::ClosedLoop::create(*experiment_, busy_condition(), spec, error);
    auto injected = sim::ClosedLoop::create(*experiment_, busy_condition(), spec, error);
    ASSERT_TRUE(plain && injected) << error;
    // Zero offsets written out (as a caller filling the struct would) change nothing either.
    sim::TickInjection zero;
    zero.reference_offset_rad.fill(0.0);
    zero.measured_position_offset_rad.fill(0.0);
    zero.measured_velocity_offset_rad_s.fill(0.0);
    zero.disturbance_torque_nm.fill(0.0);
    const std::size_t n = plain->samples();
    for (std::size_t k = 0; k < n; ++k) {
      const bool advance = k + 1 < n;
      const sim::TickResult a = plain->tick(k, advance);
      const sim::TickResult b =
          injected->tick(injected->sample(k), k % 2 == 0 ? sim::TickInjection{} : zero, advance);
      expect_same_tick(a, b, k);
      for (std::size_t i = 0; i < kJ; ++i) {
        const pid::Gains<double> ga = plain->controller().gains(i);
        const pid::Gains<double> gb = injected->controller().gains(i);
        ASSERT_TRUE(same_bits(ga.kp, gb.kp) && same_bits(ga.ki, gb.ki) && same_bits(ga.kd, gb.kd))
            << "tick " << k << " joint " << i;
        ASSERT_TRUE(same_bits(plain->controller().pid(i).integral(),
                              injected->controller().pid(i).integral()));
      }
    }
    for (std::size_t i = 0; i < kJ; ++i) {
      EXPECT_TRUE(same_bits(plain->plant().position()[i], injected->plant().position()[i]));
      EXPECT_TRUE(same_bits(plain->plant().velocity()[i], injected->plant().velocity()[i]));
    }
  }
}

// An encoder of N counts: the controller gets the angle rounded to 2π/N and the rate differenced
// from it over the plant's last step, exactly as a plain loop given those readings by injection.
TEST_F(ClosedLoopTest, AnEncoderFeedsTheControllerQuantisedAnglesAndDifferencedRates) {
  sim::Condition c;
  c.effects.encoder_counts = 2048;
  const double count = 2.0 * 3.14159265358979323846 / 2048.0;
  std::string error;
  auto encoded = sim::ClosedLoop::create(*experiment_, c, controller::paper_pid(), error);
  auto plain =
      sim::ClosedLoop::create(*experiment_, sim::Condition{}, controller::paper_pid(), error);
  ASSERT_TRUE(encoded && plain) << error;
  robot::JointVector last{};
  for (std::size_t i = 0; i < kJ; ++i)
    last[i] = std::nearbyint(plain->plant().position()[i] / count) * count;
  for (std::size_t k = 0; k + 1 < encoded->samples(); ++k) {
    sim::TickInjection readings;
    for (std::size_t i = 0; i < kJ; ++i) {
      const double now = std::nearbyint(plain->plant().position()[i] / count) * count;
      readings.measured_position_rad[i] = now;
      readings.measured_velocity_rad_s[i] =
          k == 0 ? plain->plant().velocity()[i] : (now - last[i]) / plain->sample(k - 1).dt_s;
      last[i] = now;
    }
    const sim::TickResult a = encoded->tick(k);
    const sim::TickResult b = plain->tick(plain->sample(k), readings);
    for (std::size_t i = 0; i < kJ; ++i)
      ASSERT_TRUE(same_bits(a.torque_nm[i], b.torque_nm[i]))
          << "tick " << k << " joint " << i << ": " << a.torque_nm[i] << " " << b.torque_nm[i];
  }
}

// A delay of one tick: the torque reaching the joint over tick k is the command of tick k - 1.
TEST_F(ClosedLoopTest, ADelayOfOneTickAppliesThePreviousTicksCommand) {
  sim::Condition c;
  c.effects.delay_s = experiment_->options().tick_s;
  std::string error;
  auto loop = sim::ClosedLoop::create(*experiment_, c, controller::paper_pid(), error);
  ASSERT_TRUE(loop) << error;
  robot::JointVector previous{};
  for (std::size_t k = 0; k + 1 < loop->samples(); ++k) {
    const sim::TickResult r = loop->tick(k);
    EXPECT_EQ(loop->plant().applied_torque(), previous) << "tick " << k;
    previous = r.torque_nm;
  }
}

TEST_F(ClosedLoopTest, AnInjectedNonFiniteMeasurementFaultsItsJointOnly) {
  std::string error;
  auto loop =
      sim::ClosedLoop::create(*experiment_, busy_condition(), controller::paper_fuzzy(), error);
  ASSERT_TRUE(loop) << error;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const auto faulted_joints = [&](const sim::TickResult& r) {
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < kJ; ++i)
      if (is_fault(r.command.joint_status[i])) out.push_back(i);
    return out;
  };
  const auto expect_fault_on = [&](const sim::TickResult& r, std::size_t joint) {
    EXPECT_EQ(faulted_joints(r), std::vector<std::size_t>{joint});
    EXPECT_EQ(r.command.joint_status[joint], Status::NonFiniteInput);
    EXPECT_EQ(r.plant, robot::PlantStatus::Ok);  // the other joints are controlled as usual
  };
  std::size_t k = 0;
  (void)loop->tick(k++);

  sim::TickInjection nan_position;  // joint 3 reads NaN
  nan_position.measured_position_rad[2] = nan;
  const robot::JointVector true_position = loop->plant().position();
  const sim::TickResult r1 = loop->tick(loop->sample(k++), nan_position);
  expect_fault_on(r1, 2);
  EXPECT_EQ(r1.theta, true_position);  // the plant's own state is not what the sensor read

  sim::TickInjection inf_velocity;  // joint 6's velocity reads -inf
  inf_velocity.measured_velocity_rad_s[5] = -inf;
  expect_fault_on(loop->tick(loop->sample(k++), inf_velocity), 5);

  sim::TickInjection offset;  // joint 1's position sensor adds +inf
  offset.measured_position_offset_rad[0] = inf;
  expect_fault_on(loop->tick(loop->sample(k++), offset), 0);

  // A finite bias is no fault: it moves the command of its joint alone.
  auto twin =
      sim::ClosedLoop::create(*experiment_, busy_condition(), controller::paper_fuzzy(), error);
  auto biased =
      sim::ClosedLoop::create(*experiment_, busy_condition(), controller::paper_fuzzy(), error);
  ASSERT_TRUE(twin && biased) << error;
  sim::TickInjection bias;
  bias.measured_position_offset_rad[3] = 0.01;
  const sim::TickResult a = twin->tick(0);
  const sim::TickResult b = biased->tick(biased->sample(0), bias);
  EXPECT_TRUE(faulted_joints(b).empty());
  for (std::size_t i = 0; i < kJ; ++i) {
    if (i == 3) {
      EXPECT_LT(b.command.output[i], a.command.output[i]);  // reads ahead: pushes less
    } else {
      EXPECT_TRUE(same_bits(a.command.output[i], b.command.output[i])) << i;
    }
  }
}

// Fixed PID, K = (4, 0.001 / 0.05, 100 x 0.05) continuous: only the integral term, Ki e dt,
// sees dt on the first tick.
TEST_F(ClosedLoopTest, AControllerDtChangesTheCommandWhileThePlantAdvancesThePathsInterval) {
  std::string error;
  auto plain =
      sim::ClosedLoop::create(*experiment_, sim::Condition{}, controller::paper_pid(), error);
  auto skewed =
      sim::ClosedLoop::create(*experiment_, sim::Condition{}, controller::paper_pid(), error);
  ASSERT_TRUE(plain && skewed) << error;
  sim::TickInjection clock;
  clock.controller_dt_s = 0.1;
  const sim::TickResult a = plain->tick(0);
  const sim::TickResult b = skewed->tick(skewed->sample(0), clock);
  const double ki = 0.001 / 0.05;
  for (std::size_t i = 0; i < kJ; ++i) {
    const double e = a.theta_d[i] - a.theta[i];
    EXPECT_NEAR(b.command.output[i] - a.command.output[i], ki * e * (0.1 - 0.05), 1e-15);
    EXPECT_NE(b.command.output[i], a.command.output[i]);
  }
  const double interval = plain->sample(0).dt_s;
  EXPECT_EQ(interval, experiment_->path().time_s[1] - experiment_->path().time_s[0]);
  EXPECT_EQ(plain->plant().time_s(), interval);
  EXPECT_EQ(skewed->plant().time_s(), interval);

  // A bad dt faults every joint; the plant still advances, under the held commands.
  for (double bad : {0.0, -0.05, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity()}) {
    sim::TickInjection broken;
    broken.controller_dt_s = bad;
    const double before = skewed->plant().time_s();
    const sim::TickResult r = skewed->tick(skewed->sample(1), broken);
    for (std::size_t i = 0; i < kJ; ++i) {
      EXPECT_EQ(r.command.joint_status[i], Status::InvalidTimeStep) << bad;
      EXPECT_EQ(r.command.output[i], b.command.output[i]) << bad;
    }
    EXPECT_EQ(r.plant, robot::PlantStatus::Ok);
    EXPECT_EQ(skewed->plant().time_s(), before + skewed->sample(1).dt_s);
  }
}

TEST_F(ClosedLoopTest, APlantDtAdvancesThePlantByItAndLeavesTheControllerAlone) {
  std::string error;
  auto plain =
      sim::ClosedLoop::create(*experiment_, sim::Condition{}, controller::paper_fuzzy(), error);
  auto late =
      sim::ClosedLoop::create(*experiment_, sim::Condition{}, controller::paper_fuzzy(), error);
  ASSERT_TRUE(plain && late) << error;
  sim::TickInjection jitter;
  jitter.plant_dt_s = 0.07;
  const sim::TickResult a = plain->tick(0);
  const sim::TickResult b = late->tick(late->sample(0), jitter);
  expect_same_tick(a, b, 0);  // all of it happens before the plant step
  EXPECT_EQ(late->plant().time_s(), 0.07);
  for (std::size_t i = 0; i < kJ; ++i)
    EXPECT_GT(std::fabs(late->plant().velocity()[i]), std::fabs(plain->plant().velocity()[i]));
}

TEST_F(ClosedLoopTest, ResetPlantPutsThePlantAtTheGivenState) {
  std::string error;
  auto loop =
      sim::ClosedLoop::create(*experiment_, busy_condition(), controller::paper_fuzzy(), error);
  ASSERT_TRUE(loop) << error;
  for (std::size_t k = 0; k < 10; ++k)
    (void)loop->tick(k);
  const robot::JointVector q = {0.1, -0.2, 0.3, -0.4, 0.5, -0.6};
  const robot::JointVector qd = {0.01, 0.02, -0.03, 0.04, -0.05, 0.06};
  loop->reset_plant(q, qd);
  EXPECT_EQ(loop->plant().position(), q);
  EXPECT_EQ(loop->plant().velocity(), qd);
  EXPECT_EQ(loop->plant().time_s(), 0.0);
  const sim::TickResult r = loop->tick(10);
  EXPECT_EQ(r.theta, q);
  EXPECT_EQ(r.theta_dot, qd);
}

// Fixed PID: the first tick's command is Kp e + Ki e dt + Kd ec, so a reference offset d moves it
// by (Kp + Ki dt) d on its joint alone.
TEST_F(ClosedLoopTest, AReferenceOffsetShiftsTheErrorOfItsJointOnly) {
  std::string error;
  auto plain =
      sim::ClosedLoop::create(*experiment_, sim::Condition{}, controller::paper_pid(), error);
  auto jumped =
      sim::ClosedLoop::create(*experiment_, sim::Condition{}, controller::paper_pid(), error);
  ASSERT_TRUE(plain && jumped) << error;
  sim::TickInjection jump;
  jump.reference_offset_rad[1] = 0.1;
  const sim::TickResult a = plain->tick(0);
  const sim::TickResult b = jumped->tick(jumped->sample(0), jump);
  EXPECT_EQ(b.theta_d[1], a.theta_d[1] + 0.1);
  EXPECT_NEAR(b.command.output[1] - a.command.output[1], (4.0 + 0.001) * 0.1, 1e-12);
  for (std::size_t i = 0; i < kJ; ++i) {
    EXPECT_TRUE(same_bits(a.theta_d_dot[i], b.theta_d_dot[i]));
    if (i == 1) continue;
    EXPECT_TRUE(same_bits(a.theta_d[i], b.theta_d[i])) << i;
    EXPECT_TRUE(same_bits(a.command.output[i], b.command.output[i])) << i;
  }
}

// Decoupled plant, no damping, J_i held over the tick: a torque d adds d / J_i x dt to the
// velocity of its joint and nothing to the others.
TEST_F(ClosedLoopTest, AnInjectedDisturbanceTorqueAcceleratesItsJointOnly) {
  std::string error;
  auto plain =
      sim::ClosedLoop::create(*experiment_, sim::Condition{}, controller::paper_pid(), error);
  auto pushed =
      sim::ClosedLoop::create(*experiment_, sim::Condition{}, controller::paper_pid(), error);
  ASSERT_TRUE(plain && pushed) << error;
  sim::TickInjection push;
  push.disturbance_torque_nm[0] = 50.0;
  const sim::TickResult a = plain->tick(0);
  const sim::TickResult b = pushed->tick(pushed->sample(0), push);
  expect_same_tick(a, b, 0);
  const double dt = plain->sample(0).dt_s;
  const double j0 = pushed->plant().inertia()[0];
  EXPECT_NEAR(pushed->plant().velocity()[0] - plain->plant().velocity()[0], 50.0 / j0 * dt, 1e-12);
  EXPECT_GT(pushed->plant().velocity()[0] - plain->plant().velocity()[0], 0.0);
  for (std::size_t i = 1; i < kJ; ++i) {
    EXPECT_TRUE(same_bits(plain->plant().velocity()[i], pushed->plant().velocity()[i])) << i;
    EXPECT_TRUE(same_bits(plain->plant().position()[i], pushed->plant().position()[i])) << i;
  }
}

TEST_F(ClosedLoopTest, TheCyclicPathPlaysForwardsThenBackwardsWithoutEnd) {
  std::string error;
  auto loop =
      sim::ClosedLoop::create(*experiment_, sim::Condition{}, controller::paper_pid(), error);
  ASSERT_TRUE(loop) << error;
  const std::size_t n = loop->samples();
  const std::uint64_t cycle = 2 * (n - 1);
  for (std::uint64_t t = 0; t + 1 < n; ++t) {  // the first leg is the path itself
    const sim::PathSample c = loop->cyclic_sample(t);
    const sim::PathSample s = loop->sample(t);
    EXPECT_TRUE(same_bits(c.t_s, s.t_s)) << t;
    EXPECT_TRUE(same_bits(c.dt_s, s.dt_s)) << t;
    EXPECT_EQ(c.theta_d, s.theta_d) << t;
    EXPECT_EQ(c.theta_d_dot, s.theta_d_dot) << t;
  }
  for (std::uint64_t t = n - 1; t < 3 * cycle; ++t) {
    const std::uint64_t phase = t % cycle;
    const bool back = phase >= n - 1;
    const sim::PathSample c = loop->cyclic_sample(t);
    const sim::PathSample s = loop->sample(static_cast<std::size_t>(back ? cycle - phase : phase));
    EXPECT_EQ(c.theta_d, s.theta_d) << t;
    for (std::size_t i = 0; i < kJ; ++i)
      EXPECT_EQ(c.theta_d_dot[i], back ? -s.theta_d_dot[i] : s.theta_d_dot[i]) << t;
    EXPECT_NEAR(c.t_s, static_cast<double>(t) * loop->tick_s(), 1e-9) << t;
    EXPECT_NEAR(c.dt_s, loop->tick_s(), 1e-9) << t;
  }
  // B is reached once per cycle, A at every cycle's start.
  EXPECT_EQ(loop->cyclic_sample(n - 1).theta_d, experiment_->path().position_rad.back());
  EXPECT_EQ(loop->cyclic_sample(cycle).theta_d, experiment_->path().position_rad.front());
  EXPECT_EQ(loop->cyclic_sample(5 * cycle + 7).theta_d, experiment_->path().position_rad[7]);
}

// A condition the experiment refuses (here a NaN payload and a gear on joints without the motor
// side it needs) builds no loop, whichever create() is given the controller, and the error names
// the condition and what is wrong.
TEST_F(ClosedLoopTest, EitherCreateRefusesAConditionTheExperimentRefuses) {
  const controller::ControllerSpec spec = controller::paper_pid();
  const robot::JointVector limit = experiment_->output_limit(busy_condition(), spec.units.gains);
  std::array<supervisor::FuzzyPidConfig<double>, kJ> configs;
  for (std::size_t i = 0; i < kJ; ++i)
    configs[i] = controller::fuzzy_pid_config(spec, i, limit[i]);
  sim::Condition nan_payload = busy_condition();
  nan_payload.name = "nan-payload";
  nan_payload.payload_scale = std::nan("");
  sim::Condition geared = busy_condition();
  geared.name = "geared";
  geared.effects.joint_resonance_hz.fill(12.0);
  sim::ExperimentOptions no_armature = experiment_->options();
  no_armature.plant.armature_kgm2.fill(0.0);
  std::string error;
  const auto bare = sim::Experiment::create(*model_, robot::paper_path_spec(), no_armature, error);
  ASSERT_TRUE(bare) << error;
  struct Refused {
    const sim::Experiment* experiment;
    const sim::Condition* condition;
    const char* says;
  };
  for (const Refused& r : {Refused{&*experiment_, &nan_payload, "payload_scale"},
                           Refused{&*bare, &geared, "needs an armature > 0 on joint 1"}}) {
    error.clear();
    EXPECT_FALSE(sim::ClosedLoop::create(*r.experiment, *r.condition, spec, error));
    EXPECT_NE(error.find("condition " + r.condition->name + ": "), std::string::npos) << error;
    EXPECT_NE(error.find(r.says), std::string::npos) << error;
    auto joints = controller::JointControllers::create(spec, configs, error);
    ASSERT_TRUE(joints) << error;
    error.clear();
    EXPECT_FALSE(sim::ClosedLoop::create(*r.experiment, *r.condition, std::move(*joints), error));
    EXPECT_NE(error.find(r.says), std::string::npos) << error;
  }
}

// What a file cannot say (a gain update per joint, an integral limit): the joints run the
// configurations they were given, and the spec's own configurations run like the spec.
TEST_F(ClosedLoopTest, AControllerBuiltWithAConfigurationPerJointRunsThem) {
  const controller::ControllerSpec spec = controller::paper_fuzzy();
  const sim::Condition cond = busy_condition();
  const robot::JointVector limit = experiment_->output_limit(cond, spec.units.gains);
  std::array<supervisor::FuzzyPidConfig<double>, kJ> configs;
  for (std::size_t i = 0; i < kJ; ++i)
    configs[i] = controller::fuzzy_pid_config(spec, i, limit[i]);
  std::string error;
  auto from_spec = sim::ClosedLoop::create(*experiment_, cond, spec, error);
  auto same = controller::JointControllers::create(spec, configs, error);
  ASSERT_TRUE(from_spec && same) << error;
  auto same_loop = sim::ClosedLoop::create(*experiment_, cond, std::move(*same), error);
  ASSERT_TRUE(same_loop) << error;

  for (std::size_t i = 3; i < kJ; ++i) {
    configs[i].gain_update = supervisor::GainUpdate::Incremental;
    configs[i].pid.integral_min = -0.5;
    configs[i].pid.integral_max = 0.5;
  }
  auto mixed = controller::JointControllers::create(spec, configs, error);
  ASSERT_TRUE(mixed) << error;
  auto mixed_loop = sim::ClosedLoop::create(*experiment_, cond, std::move(*mixed), error);
  ASSERT_TRUE(mixed_loop) << error;
  EXPECT_EQ(mixed_loop->controller().pid(4).config().integral_max, 0.5);
  EXPECT_EQ(mixed_loop->controller().pid(1).config().integral_max,
            std::numeric_limits<double>::infinity());

  // Tick 0 runs K0 + S dK everywhere; at tick 1 the incremental joints add to tick 0's gains.
  for (std::size_t k = 0; k < 2; ++k) {
    expect_same_tick(from_spec->tick(k), same_loop->tick(k), k);
    (void)mixed_loop->tick(k);
  }
  for (std::size_t i = 0; i < kJ; ++i) {
    const pid::Gains<double> g = from_spec->controller().gains(i);
    const pid::Gains<double> m = mixed_loop->controller().gains(i);
    if (i < 3) {
      EXPECT_TRUE(same_bits(g.kp, m.kp) && same_bits(g.ki, m.ki) && same_bits(g.kd, m.kd)) << i;
    } else {
      EXPECT_NE(g.kp, m.kp) << i;
    }
  }

  configs[4].pid.integral_min = 1.0;  // above its integral_max of 0.5
  EXPECT_FALSE(controller::JointControllers::create(spec, configs, error));
  EXPECT_FALSE(error.empty());
}

TEST_F(ClosedLoopTest, NegativeInitialErrorStartsAheadAndReverseRunsBToA) {
  sim::Condition ahead;
  ahead.initial_error_rad = -0.05;
  const auto r = experiment_->run(ahead, controller::paper_pid());
  ASSERT_TRUE(r.ok) << r.error;
  for (std::size_t i = 0; i < kJ; ++i)
    EXPECT_NEAR(r.rows[i].error, -0.05, 1e-15);  // theta_d - (theta_d + 0.05)
  sim::Condition back;
  back.reverse = true;
  const auto b = experiment_->run(back, controller::paper_pid());
  ASSERT_TRUE(b.ok) << b.error;
  const auto& fwd = experiment_->path().position_rad;
  for (std::size_t i = 0; i < kJ; ++i) {
    EXPECT_NEAR(b.rows[i].theta_d, fwd.back()[i], 1e-9);
    EXPECT_NEAR(b.rows[b.rows.size() - kJ + i].theta_d, fwd.front()[i], 1e-9);
  }
}

// Largest |theta - theta_fine| of the paper's PID on `c` with the default plant step against the
// same run with every step at most `fine_step_s`.
double finer_step_error(const sim::Experiment& ex, sim::Condition c, double fine_step_s) {
  const sim::RunResult coarse = ex.run(c, controller::paper_pid());
  c.effects.plant_step_s = fine_step_s;
  const sim::RunResult fine = ex.run(c, controller::paper_pid());
  EXPECT_TRUE(coarse.ok && fine.ok) << coarse.error << fine.error;
  EXPECT_EQ(coarse.rows.size(), fine.rows.size());
  double worst = 0.0;
  for (std::size_t k = 0; k < coarse.rows.size() && k < fine.rows.size(); ++k)
    worst = std::fmax(worst, std::fabs(coarse.rows[k].theta - fine.rows[k].theta));
  return worst;
}

// sim_ab --friction 100: the default step (1 ms decoupled, cut by the plant's
// stiffness bound h·λ <= 0.25, and coupled the same bound instead of 50 ms) against steps of
// at most 0.1 ms.
TEST_F(ClosedLoopTest, AtHighFrictionTheDefaultStepIsWithinAMicroradianOfATenTimesFinerStep) {
  sim::Condition c;
  c.friction_per_s = 100.0;
  const double decoupled = finer_step_error(*experiment_, c, 1e-4);
  c.dynamics = robot::PlantCoupling::Coupled;
  c.gravity = true;
  const double coupled = finer_step_error(*experiment_, c, 1e-4);
  std::printf(
      "[ accuracy ] friction 100: max |theta - theta_fine| %.2e rad decoupled, %.2e rad "
      "coupled with gravity\n",
      decoupled, coupled);
  EXPECT_LT(decoupled, 1e-6);
  EXPECT_LT(coupled, 1e-6);
}

// coulomb_smoothing: the condition's v_ε reaches the plant (0: the plant's 0.001 rad/s), and
// widening it 30x -- what tuning/robust_drive.toml trains with, for the step rule's sake -- keeps
// what Coulomb friction does to the paper's PID: the wrist, whose torque stays below 1.5 % of its
// limit, sticks behind the path either way, and the summed ITAE moves by less than a fifth.
TEST_F(ClosedLoopTest, AWiderCoulombSmoothingReachesThePlantAndKeepsAStuckWristStuck) {
  sim::Condition c;
  c.initial_error_rad = 0.05;
  c.effects.coulomb_nm = {70.0, 100.0, 50.0, 6.0, 6.0, 3.0};
  EXPECT_EQ(experiment_->plant_config(c).coulomb_smoothing_rad_s, 1e-3);
  const sim::RunResult stiff = experiment_->run(c, controller::paper_pid());
  c.effects.coulomb_smoothing_rad_s = 0.03;
  EXPECT_EQ(experiment_->plant_config(c).coulomb_smoothing_rad_s, 0.03);
  const sim::RunResult wide = experiment_->run(c, controller::paper_pid());
  ASSERT_TRUE(stiff.ok && wide.ok) << stiff.error << wide.error;
  // The ITAE summed over the joints (rectangle rule over the ticks) and joint 6's largest |e|.
  const double tick_s = experiment_->options().tick_s;
  const auto measure = [tick_s](const sim::RunResult& r, double& itae, double& wrist) {
    itae = wrist = 0.0;
    for (const sim::TrajectoryRow& row : r.rows) {
      itae += row.t_s * std::fabs(row.error) * tick_s;
      if (row.joint == 6) wrist = std::fmax(wrist, std::fabs(row.error));
    }
  };
  double itae_stiff = 0.0, itae_wide = 0.0, wrist_stiff = 0.0, wrist_wide = 0.0;
  measure(stiff, itae_stiff, wrist_stiff);
  measure(wide, itae_wide, wrist_wide);
  std::printf(
      "[ friction ] summed ITAE %.3f (0.001 rad/s) %.3f (0.03 rad/s); joint 6 max |e| "
      "%.3f %.3f rad\n",
      itae_stiff, itae_wide, wrist_stiff, wrist_wide);
  EXPECT_GT(wrist_stiff, 0.3);
  EXPECT_GT(wrist_wide, 0.3);
  EXPECT_NEAR(itae_wide / itae_stiff, 1.0, 0.2);
}

// What the velocity observer is for: with a 2^14-count encoder at the 50 ms tick, one tick of
// delay, a current loop and a 12 Hz gear, the drive re-tune's PID (data/drive_retune_pid.toml)
// reverses its command with the encoder's counts through its D term; the same gains with a 1.2 Hz observer (tests/sim/data/observer_pid.toml)
// reverse on a few per cent of the ticks, still track, and every run stays without faults.
TEST_F(ClosedLoopTest, AVelocityObserverQuietsTheCommandOfACoarseEncoder) {
  sim::Condition c;
  c.initial_error_rad = 0.05;
  c.effects.encoder_counts = 16384;
  c.effects.delay_s = 0.05;
  c.effects.torque_bandwidth_hz = 50.0;
  c.effects.joint_resonance_hz.fill(12.0);
  c.effects.joint_damping_ratio = 0.05;
  const auto worst = [&](const controller::ControllerSpec& spec, double& itae) {
    const sim::RunResult r = experiment_->run(c, spec);
    EXPECT_TRUE(r.ok) << r.error;
    EXPECT_FALSE(r.tracking_faults.any());
    std::array<std::vector<double>, kJ> u;
    itae = 0.0;
    for (const sim::TrajectoryRow& row : r.rows) {
      u[static_cast<std::size_t>(row.joint - 1)].push_back(row.u);
      itae += row.t_s * std::fabs(row.error) * experiment_->options().tick_s;
    }
    double pct = 0.0;
    for (const auto& joint : u)
      pct = std::fmax(pct, sim::reversals_pct(joint));
    return pct;
  };
  const auto load = [](const std::string& file) {
    controller::ControllerSpec spec;
    fuzzypid::FileError err;
    EXPECT_TRUE(cf::load(FUZZYPID_SOURCE_DIR "/" + file, spec, err)) << err.to_string();
    return spec;
  };
  double itae_rates = 0.0, itae_observer = 0.0;
  const double rates = worst(load("tests/sim/data/drive_retune_pid.toml"), itae_rates);
  const double observer = worst(load("tests/sim/data/observer_pid.toml"), itae_observer);
  std::printf(
      "[ observer ] worst joint's reversals %.1f %% (rates) %.1f %% (observer); summed ITAE "
      "%.3f %.3f\n",
      rates, observer, itae_rates, itae_observer);
  EXPECT_GT(rates, 20.0);
  EXPECT_LT(observer, 10.0);
  EXPECT_LT(itae_observer, 1.2 * itae_rates);
}

TEST_F(ClosedLoopTest, InvalidConditionsAreRefused) {
  sim::Condition bad;
  bad.payload_scale = 0.0;
  const auto r = experiment_->run(bad, controller::paper_pid());
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("payload"), std::string::npos);
  sim::Condition step;
  step.effects.plant_step_s = -1e-3;
  const auto s = experiment_->run(step, controller::paper_pid());
  EXPECT_FALSE(s.ok);
  EXPECT_NE(s.error.find("plant_step_ms must be 0 (the default step) or within 0.001 .. 1000"),
            std::string::npos)
      << s.error;
  // 0 is the plant's default here, not "off": the message says which.
  sim::Condition stribeck;
  stribeck.effects.stribeck_velocity_rad_s = -0.1;
  const auto v = experiment_->run(stribeck, controller::paper_pid());
  EXPECT_FALSE(v.ok);
  EXPECT_NE(
      v.error.find("stribeck_velocity must be 0 (the plant's default) or within 1e-05 .. 100"),
      std::string::npos)
      << v.error;
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
  const supervisor::GainSchedule<double> s;
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
