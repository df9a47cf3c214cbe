// What sim::Experiment::run records beside the tracking error (fuzzypid/sim/experiment.hpp): the
// torque the plant received, the joint velocity, whether the torque sat at a limit, the joints
// that diverged or left their limits (fuzzypid/sim/faults.hpp), and the tool's path error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include "fuzzypid/controller/controller_spec.hpp"
#include "fuzzypid/robot/path.hpp"
#include "fuzzypid/robot/robot_model.hpp"
#include "fuzzypid/sim/closed_loop.hpp"
#include "fuzzypid/sim/experiment.hpp"

namespace {

using namespace fuzzypid;
constexpr std::size_t kJ = robot::kNumJoints;

std::optional<sim::Experiment> paper_experiment(const std::string& urdf, std::string& error) {
  auto loaded = robot::RobotModel::load(urdf);
  if (!loaded.model) {
    error = loaded.error;
    return std::nullopt;
  }
  sim::ExperimentOptions options;
  options.plant.armature_kgm2 = robot::kEr50ArmatureKgm2;  // the bundled ER50-C20's motors
  return sim::Experiment::create(*loaded.model, robot::paper_path_spec(), options, error);
}

// The paper's PID with its gains times `scale`.
controller::ControllerSpec scaled_paper_pid(double scale) {
  controller::ControllerSpec s = controller::paper_pid();
  s.gains.kp *= scale;
  s.gains.ki *= scale;
  s.gains.kd *= scale;
  return s;
}

TEST(RunOutputs, RowsCarryTheTorqueThePlantReceivedAndTheTrueVelocity) {
  std::string error;
  const auto ex = paper_experiment(robot::default_urdf_path(), error);
  ASSERT_TRUE(ex) << error;
  sim::Condition c;
  c.name = "limited";
  c.torque_limit_rad_s2 = 0.3;  // low enough that the start transient sits on it
  const controller::ControllerSpec spec = controller::paper_pid();
  const sim::RunResult r = ex->run(c, spec);
  ASSERT_TRUE(r.ok) << r.error;
  const robot::JointVector limit = ex->torque_limit(c);
  const std::size_t ticks = r.rows.size() / kJ;
  ASSERT_EQ(ticks, ex->ticks());
  // The same loop ticked by hand: its plant's applied torque and velocity.
  auto loop = sim::ClosedLoop::create(*ex, c, spec, error);
  ASSERT_TRUE(loop) << error;
  std::size_t saturated = 0;
  for (std::size_t k = 0; k < ticks; ++k) {
    const sim::TickResult t = loop->tick(k, k + 1 < ticks);
    for (std::size_t i = 0; i < kJ; ++i) {
      const sim::TrajectoryRow& row = r.rows[k * kJ + i];
      EXPECT_EQ(row.tau_nm, loop->plant().applied_torque()[i]) << "tick " << k << " joint " << i;
      EXPECT_EQ(row.omega_rad_s, t.theta_dot[i]);
      EXPECT_LE(std::fabs(row.tau_nm), limit[i] * (1.0 + 1e-12));
      // At the limit exactly when flagged.
      EXPECT_EQ(row.saturated, std::fabs(row.tau_nm) >= (1.0 - 1e-9) * limit[i]);
      if (row.saturated) ++saturated;
      // Before the last sample: the clamped J^_i u_i of this tick.
      if (k + 1 < ticks) {
        const double asked = ex->nominal_inertia()[i] * row.u;
        EXPECT_NEAR(row.tau_nm, std::fmin(std::fmax(asked, -limit[i]), limit[i]), 1e-9 * limit[i]);
      } else {
        EXPECT_EQ(row.tau_nm, r.rows[(k - 1) * kJ + i].tau_nm);  // repeats the one before
      }
    }
  }
  EXPECT_GT(saturated, 0u);
  EXPECT_EQ(r.rows[0].omega_rad_s, 0.0);  // starts at rest
}

TEST(RunOutputs, ADivergingRunIsCountedAndGoesOnUnlessTheTunersEarlyStopIsAsked) {
  std::string error;
  const auto ex = paper_experiment(robot::default_urdf_path(), error);
  ASSERT_TRUE(ex) << error;
  const sim::Condition c;
  // The paper's PID itself: nothing near 1 rad.
  const sim::RunResult nominal = ex->run(c, controller::paper_pid());
  ASSERT_TRUE(nominal.ok);
  EXPECT_FALSE(nominal.tracking_faults.any());
  EXPECT_EQ(nominal.fault_ticks, 0u);

  // Gains x10: some joint passes 1 rad; the run goes on to the end of the path.
  const sim::RunResult r = ex->run(c, scaled_paper_pid(10.0));
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_FALSE(r.diverged);
  EXPECT_EQ(r.rows.size(), ex->ticks() * kJ);
  ASSERT_TRUE(r.tracking_faults.any());
  EXPECT_EQ(r.fault_ticks, r.tracking_faults.ticks);  // no controller fault among them
  // Each joint's divergence ticks are its rows past 1 rad; the ticks with a fault of any kind
  // include them (the ×10 loop also rings on its torque limits: limit cycles).
  std::size_t faulted_ticks = 0;
  for (std::size_t k = 0; k < ex->ticks(); ++k) {
    bool any = false;
    for (std::size_t i = 0; i < kJ; ++i)
      any = any || std::fabs(r.rows[k * kJ + i].error) > 1.0;
    if (any) ++faulted_ticks;
  }
  EXPECT_GE(r.tracking_faults.ticks, faulted_ticks);
  std::size_t cycling = 0;
  for (std::size_t i = 0; i < kJ; ++i) {
    std::size_t past = 0;
    for (std::size_t k = 0; k < ex->ticks(); ++k)
      past += std::fabs(r.rows[k * kJ + i].error) > 1.0 ? 1 : 0;
    EXPECT_EQ(r.tracking_faults.divergence[i].ticks, past) << "joint " << i + 1;
    cycling += r.tracking_faults.limit_cycle[i].ticks;
  }
  EXPECT_GT(cycling, 0u);
  for (std::size_t i = 0; i < kJ; ++i) {
    const sim::JointFault& f = r.tracking_faults.divergence[i];
    if (f.ticks == 0) continue;
    // The first row past 1 rad.
    std::size_t k = 0;
    while (std::fabs(r.rows[k * kJ + i].error) <= 1.0)
      ++k;
    EXPECT_EQ(f.first_t_s, r.rows[k * kJ + i].t_s);
    EXPECT_EQ(f.first_value_rad, std::fabs(r.rows[k * kJ + i].error));
  }
  // A larger bound sees no divergence (the limit cycles stay).
  sim::RunLimits loose;
  loose.divergence_rad = 100.0;
  const sim::TrackingFaults wide = ex->run(c, scaled_paper_pid(10.0), loose).tracking_faults;
  for (std::size_t i = 0; i < kJ; ++i)
    EXPECT_EQ(wide.divergence[i].ticks, 0u) << "joint " << i + 1;
  // The tuner's early stop: the run ends at the first tick past the bound, as before.
  sim::RunLimits tuner;
  tuner.max_error_rad = 1.0;
  const sim::RunResult stopped = ex->run(c, scaled_paper_pid(10.0), tuner);
  EXPECT_TRUE(stopped.diverged);
  EXPECT_LT(stopped.rows.size(), r.rows.size());
  std::size_t diverged_ticks = 0;
  for (const sim::JointFault& f : stopped.tracking_faults.divergence)
    diverged_ticks = std::max(diverged_ticks, f.ticks);
  EXPECT_EQ(diverged_ticks, 1u);
}

TEST(RunOutputs, AJointOutsideItsUrdfLimitsIsAFault) {
  std::string error;
  const auto bundled = paper_experiment(robot::default_urdf_path(), error);
  ASSERT_TRUE(bundled) << error;
  // The bundled arm with joint 5's upper limit 0.1 rad above the path's start (the path moves
  // joint 5 down from there): starting 0.2 rad ahead puts the joint outside it at t = 0.
  const double start = bundled->path().position_rad.front()[4];
  std::ifstream in(robot::default_urdf_path());
  std::stringstream text;
  text << in.rdbuf();
  std::string urdf = text.str();
  const std::string j5 = R"(lower="-2.0943951023931953" upper="2.0943951023931953")";
  const std::size_t at = urdf.find(j5);
  ASSERT_NE(at, std::string::npos);
  urdf.replace(at, j5.size(),
               "lower=\"-2.0943951023931953\" upper=\"" + std::to_string(start + 0.1) + "\"");
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / "fuzzypid_test_run_outputs_limits.urdf";
  std::ofstream(file) << urdf;
  const auto ex = paper_experiment(file.string(), error);
  std::filesystem::remove(file);
  ASSERT_TRUE(ex) << error;
  sim::Condition c;
  c.initial_error_rad = -0.2;
  const sim::RunResult r = ex->run(c, controller::paper_pid());
  ASSERT_TRUE(r.ok) << r.error;
  const sim::JointFault& f = r.tracking_faults.joint_limit[4];
  ASSERT_GT(f.ticks, 0u);
  EXPECT_EQ(f.first_t_s, 0.0);
  EXPECT_DOUBLE_EQ(f.first_value_rad, start + 0.2);
  for (std::size_t i = 0; i < kJ; ++i) {
    if (i != 4) {
      EXPECT_EQ(r.tracking_faults.joint_limit[i].ticks, 0u) << "joint " << i + 1;
    }
  }
  // The same start inside the limits: no fault.
  c.initial_error_rad = -0.05;
  EXPECT_EQ(ex->run(c, controller::paper_pid()).tracking_faults.joint_limit[4].ticks, 0u);
}

TEST(RunOutputs, TheToolPathErrorIsTheDistanceOfTheForwardKinematics) {
  std::string error;
  const auto ex = paper_experiment(robot::default_urdf_path(), error);
  ASSERT_TRUE(ex) << error;
  const sim::RunResult r = ex->run(sim::Condition{}, controller::paper_pid());
  ASSERT_TRUE(r.ok);
  const sim::TcpTrack track = sim::tcp_track(ex->model(), r.rows);
  ASSERT_EQ(track.t_s.size(), ex->ticks());
  double max_mm = 0.0, sum_sq = 0.0;
  robot::RobotData data(ex->model());
  for (std::size_t k = 0; k < ex->ticks(); ++k) {
    robot::JointVector qd{}, q{};
    for (std::size_t i = 0; i < kJ; ++i) {
      qd[i] = r.rows[k * kJ + i].theta_d;
      q[i] = r.rows[k * kJ + i].theta;
    }
    const double d = (ex->model().forward_kinematics(q, data).position_m -
                      ex->model().forward_kinematics(qd, data).position_m)
                         .norm() *
                     1e3;
    max_mm = std::max(max_mm, d);
    sum_sq += d * d;
  }
  const sim::TcpErrorMetrics m = sim::tcp_error_metrics(track);
  EXPECT_DOUBLE_EQ(m.max_mm, max_mm);
  EXPECT_NEAR(m.rms_mm, std::sqrt(sum_sq / static_cast<double>(ex->ticks())), 1e-12 * max_mm);
  EXPECT_GT(m.max_mm, 0.0);
}

}  // namespace
