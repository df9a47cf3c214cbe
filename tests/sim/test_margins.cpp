// The frozen-gain margins of sim/margins.hpp against a closed form, against the closed loop's
// eigenvalues and against a simulation of the library's pid::Pid on an exact zero-order-hold
// joint (no sim_ab).
#include "fuzzypid/sim/margins.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <deque>
#include <functional>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid/pid/pid.hpp"
#include "fuzzypid/robot/path.hpp"
#include "fuzzypid/robot/plant.hpp"
#include "fuzzypid/robot/robot_model.hpp"
#include "fuzzypid/sim/certify.hpp"
#include "fuzzypid/sim/experiment.hpp"
#include "fuzzypid_support/uniform_real.hpp"

namespace {

using fuzzypid::pid::DerivativeSource;
using fuzzypid::sim::JointLoop;
using fuzzypid::sim::LoopMargins;

// The gain factor at which the closed loop's spectral radius reaches 1, by bisection.
double eigen_gain_boundary(const JointLoop& loop, double lo, double hi) {
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    if (fuzzypid::sim::closed_loop_spectral_radius(loop, mid) < 1.0)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

// Exact motion of θ̈ = c u − a θ̇ over τ seconds with u constant.
void advance(double& theta, double& omega, double u, double a, double c, double tau) {
  const double q = std::exp(-a * tau);
  const double p = a > 0.0 ? (1.0 - q) / a : tau;
  const double bt = a > 0.0 ? (tau - p) / a : tau * tau / 2.0;
  theta += p * omega + c * bt * u;
  omega = q * omega + c * p * u;
}

// Largest |θ| over the last tenth of a run of pid::Pid (gains × scale; with a velocity observer,
// the plant's gain × scale, as margins() defines the loop gain then) on θ̈ = c u − a θ̇ with its
// output reaching the plant delay_s later (held from then on until the next one arrives), stepped
// exactly, from θ = 0.05 rad at rest.
double simulate_delay(const JointLoop& loop, double scale, double delay_s, int ticks) {
  const bool observed = loop.derivative == DerivativeSource::Observer;
  const double gain_scale = observed ? 1.0 : scale;
  fuzzypid::pid::Config<double> config;
  config.gains = {gain_scale * loop.gains.kp, gain_scale * loop.gains.ki,
                  gain_scale * loop.gains.kd};
  config.derivative_filter_s = loop.derivative_filter_s;
  config.derivative_source = loop.derivative;
  config.observer_bandwidth_hz = loop.observer_bandwidth_hz;
  config.observer_delay_ticks = loop.observer_delay_ticks;
  config.observer_output_per_unit = 1.0 / loop.observer_plant_gain;
  config.anti_windup = fuzzypid::pid::AntiWindup::None;
  fuzzypid::pid::Pid<double> pid(config);
  const double h = loop.tick_s, a = loop.damping_per_s;
  const double c = observed ? scale * loop.plant_gain : loop.plant_gain;
  // delay_s = (m + f) h: over tick k the plant sees u_{k-m-1} for f h, then u_{k-m}.
  const double ticks_delay = delay_s / h;
  const double near = std::round(ticks_delay);
  const int m = std::abs(ticks_delay - near) < 1e-9 ? static_cast<int>(near)
                                                    : static_cast<int>(std::floor(ticks_delay));
  const double f = std::abs(ticks_delay - near) < 1e-9 ? 0.0 : ticks_delay - m;
  double theta = 0.05, omega = 0.0, peak = 0.0;
  std::deque<double> line(static_cast<std::size_t>(m + 1), 0.0);  // u_{k-m-1} .. u_{k-1}
  for (int k = 0; k < ticks; ++k) {
    fuzzypid::pid::Input<double> in;
    in.measurement = theta;
    in.measurement_rate = omega;
    // Only a diverging run overflows.
    if (pid.update(in, h) != fuzzypid::Status::Ok) return INFINITY;
    line.push_back(pid.output());
    const double older = line.front();  // u_{k-m-1}
    line.pop_front();
    const double newer = line.front();  // u_{k-m}
    if (f > 0.0) advance(theta, omega, older, a, c, f * h);
    advance(theta, omega, newer, a, c, (1.0 - f) * h);
    if (!(std::abs(theta) < 1e100)) return INFINITY;
    if (k >= ticks - ticks / 10) peak = std::max(peak, std::abs(theta));
  }
  return peak;
}

// The same with a whole number of ticks of delay.
double simulate(const JointLoop& loop, double scale, int delay_ticks, int ticks) {
  return simulate_delay(loop, scale, delay_ticks * loop.tick_s, ticks);
}

TEST(Margins, PdOnDoubleIntegratorMatchesClosedForm) {
  // z² + (Kp h²/2 + Kd h − 2) z + 1 + Kp h²/2 − Kd h: with Kp h < 2 Kd, the Jury conditions fail
  // first at z = −1, for the gain factor 2 / (Kd h); L(−1) = −Kd h / 2.
  JointLoop loop;
  loop.tick_s = 0.01;
  loop.plant_gain = 1.0;
  loop.gains = {400.0, 0.0, 30.0};
  const LoopMargins m = fuzzypid::sim::margins(loop);
  const double closed_form = 2.0 / (loop.gains.kd * loop.tick_s);
  ASSERT_TRUE(m.stable);
  EXPECT_NEAR(m.gain_margin_db, 20.0 * std::log10(closed_form), 1e-9);
  EXPECT_NEAR(m.phase_crossover_rad_s, M_PI / loop.tick_s, 1e-9);
  EXPECT_EQ(m.gain_margin_low_db, -INFINITY);
  EXPECT_NEAR(eigen_gain_boundary(loop, 1.0, 100.0), closed_form, 1e-6 * closed_form);
  // Phase margin: at the crossover |L| = 1 and 180° + ∠L is the margin (checked on L itself).
  const auto l = fuzzypid::sim::loop_response(loop, m.gain_crossover_rad_s);
  EXPECT_NEAR(std::abs(l), 1.0, 1e-9);
  EXPECT_NEAR(m.phase_margin_deg, 180.0 + std::arg(l) * 180.0 / M_PI, 1e-9);
  EXPECT_NEAR(m.delay_margin_s, m.phase_margin_deg * M_PI / 180.0 / m.gain_crossover_rad_s, 1e-12);
  // The disk holds the gain margin's ends inside it: α / 2 < the distance to either boundary.
  EXPECT_GT(m.disk_margin, 0.0);
  EXPECT_LT(m.disk_gain_high, closed_form);
}

TEST(Margins, GainMarginEqualsEigenvalueBoundaryForFullPid) {
  for (const DerivativeSource source : {DerivativeSource::Rates, DerivativeSource::Difference}) {
    JointLoop loop;
    loop.tick_s = 0.005;
    loop.plant_gain = 0.8;
    loop.damping_per_s = 0.7;
    loop.gains = {900.0, 1500.0, 40.0};
    loop.derivative_filter_s = 0.002;
    loop.derivative = source;
    const LoopMargins m = fuzzypid::sim::margins(loop);
    ASSERT_TRUE(m.stable);
    const double gm = std::pow(10.0, m.gain_margin_db / 20.0);
    EXPECT_NEAR(eigen_gain_boundary(loop, 1.0, 1e3), gm, 1e-6 * gm);
  }
}

TEST(Margins, ScalingByGainMarginIsTheSimulatedStabilityBoundary) {
  JointLoop loop;
  loop.tick_s = 0.01;
  loop.plant_gain = 1.3;
  loop.damping_per_s = 0.2;
  loop.gains = {300.0, 200.0, 25.0};
  loop.derivative_filter_s = 0.005;
  const LoopMargins m = fuzzypid::sim::margins(loop);
  ASSERT_TRUE(m.stable);
  const double gm = std::pow(10.0, m.gain_margin_db / 20.0);
  EXPECT_LT(simulate(loop, 0.95 * gm, 0, 40000), 1e-6);
  EXPECT_GT(simulate(loop, 1.05 * gm, 0, 40000), 1.0);
}

TEST(Margins, DelayMarginIsTheSimulatedStabilityBoundary) {
  // A fine tick so that whole ticks resolve the delay margin to better than 5 %.
  JointLoop loop;
  loop.tick_s = 0.001;
  loop.plant_gain = 1.0;
  loop.gains = {100.0, 20.0, 15.0};
  const LoopMargins m = fuzzypid::sim::margins(loop);
  ASSERT_TRUE(m.stable);
  ASSERT_GT(m.delay_margin_s, 40 * loop.tick_s);
  const int below = static_cast<int>(std::floor(0.95 * m.delay_margin_s / loop.tick_s));
  const int above = static_cast<int>(std::ceil(1.05 * m.delay_margin_s / loop.tick_s));
  EXPECT_LT(simulate(loop, 1.0, below, 200000), 1e-6);
  EXPECT_GT(simulate(loop, 1.0, above, 200000), 1.0);
  // The discrete count lies between them, and the eigenvalues agree with it.
  EXPECT_GT(m.delay_margin_ticks, below);
  EXPECT_LE(m.delay_margin_ticks, above);
  EXPECT_LT(fuzzypid::sim::closed_loop_spectral_radius(loop, 1.0, m.delay_margin_ticks - 1), 1.0);
  EXPECT_GE(fuzzypid::sim::closed_loop_spectral_radius(loop, 1.0, m.delay_margin_ticks), 1.0);
}

TEST(Margins, FractionalDelayMarginIsTheSimulatedStabilityBoundary) {
  // A coarse tick: the delay margin is a fraction of a tick, which whole ticks cannot resolve.
  JointLoop loop;
  loop.tick_s = 0.05;
  loop.plant_gain = 1.0;
  loop.gains = {172.5, 0.00045, 21.35};  // the drive re-tune's PID gains, continuous
  const LoopMargins m = fuzzypid::sim::margins(loop);
  ASSERT_TRUE(m.stable);
  ASSERT_EQ(m.delay_margin_ticks, 1);
  const double exact = m.delay_margin_exact_s;
  ASSERT_GT(exact, 0.0);
  ASSERT_LT(exact, loop.tick_s);
  EXPECT_LT(simulate_delay(loop, 1.0, 0.95 * exact, 20000), 1e-6);
  EXPECT_GT(simulate_delay(loop, 1.0, 1.05 * exact, 20000), 1.0);
  // With half that delay in the loop, the frequency response (modified z-transform) and the
  // eigenvalues agree on the gain margin.
  JointLoop late = loop;
  fuzzypid::sim::set_delay(late, 0.5 * exact);
  EXPECT_EQ(late.delay_ticks, 0);
  EXPECT_GT(late.delay_fraction, 0.0);
  const LoopMargins ml = fuzzypid::sim::margins(late);
  ASSERT_TRUE(ml.stable);
  const double gm = std::pow(10.0, ml.gain_margin_db / 20.0);
  EXPECT_NEAR(eigen_gain_boundary(late, 1.0, 100.0), gm, 1e-6 * gm);
}

TEST(Margins, RandomJointsStableBelowAndDivergentAboveGainMargin) {
  const std::uint64_t seed = 20261203;
  std::printf("seed %llu\n", static_cast<unsigned long long>(seed));
  std::mt19937_64 rng(seed);
  fuzzypid::support::UniformReal<double> unit(0.0, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 20; ++trial) {
    JointLoop loop;
    loop.tick_s = 0.001 * std::pow(50.0, unit(rng));   // 1 .. 50 ms
    loop.plant_gain = 0.5 * std::pow(4.0, unit(rng));  // J^ / J in 0.5 .. 2
    loop.damping_per_s = 2.0 * unit(rng);
    const double wb = (0.05 + 0.25 * unit(rng)) * M_PI / loop.tick_s;
    loop.gains = {wb * wb, 0.1 * wb * wb * wb, (1.0 + unit(rng)) * wb};
    loop.derivative_filter_s = 0.2 * unit(rng) * loop.tick_s;
    loop.derivative = unit(rng) < 0.5 ? DerivativeSource::Rates : DerivativeSource::Difference;
    const LoopMargins m = fuzzypid::sim::margins(loop);
    if (!m.stable || !std::isfinite(m.gain_margin_db)) continue;
    ++checked;
    const double gm = std::pow(10.0, m.gain_margin_db / 20.0);
    EXPECT_LT(simulate(loop, 0.95 * gm, 0, 40000), 1e-3) << "trial " << trial;
    EXPECT_GT(simulate(loop, 1.05 * gm, 0, 40000), 1.0) << "trial " << trial;
  }
  EXPECT_GE(checked, 15);
}

// A velocity observer in the loop (DerivativeSource::Observer, pid.hpp): the frequency response's
// gain margin (now that of the plant's gain), the state matrix's stability boundary and pid::Pid
// itself on the joint agree, over seeded random joints, bandwidths, modelled and real delays, and
// observer models that are right or off by a factor of two.
TEST(Margins, AVelocityObserverInTheLoopIsModelledAsPidRunsIt) {
  const std::uint64_t seed = 20261206;
  std::printf("seed %llu\n", static_cast<unsigned long long>(seed));
  std::mt19937_64 rng(seed);
  fuzzypid::support::UniformReal<double> unit(0.0, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 24; ++trial) {
    JointLoop loop;
    loop.tick_s = 0.005 * std::pow(10.0, unit(rng));   // 5 .. 50 ms
    loop.plant_gain = 0.5 * std::pow(4.0, unit(rng));  // J^ / J in 0.5 .. 2
    loop.damping_per_s = 2.0 * unit(rng);
    const double wb = (0.03 + 0.12 * unit(rng)) * M_PI / loop.tick_s;
    loop.gains = {wb * wb, 0.1 * wb * wb * wb, (1.0 + unit(rng)) * wb};
    loop.derivative_filter_s = 0.5 * unit(rng) * loop.tick_s;
    loop.derivative = DerivativeSource::Observer;
    loop.observer_bandwidth_hz = (0.05 + 0.3 * unit(rng)) / loop.tick_s;
    loop.observer_delay_ticks = static_cast<int>(unit(rng) * 2.0);  // 0 or 1
    loop.observer_plant_gain = unit(rng) < 0.5 ? 1.0 : 2.0 * loop.plant_gain;
    loop.delay_ticks = static_cast<int>(unit(rng) * 2.0);
    const LoopMargins m = fuzzypid::sim::margins(loop);
    if (!m.stable || !std::isfinite(m.gain_margin_db)) continue;
    ++checked;
    const double gm = std::pow(10.0, m.gain_margin_db / 20.0);
    EXPECT_NEAR(eigen_gain_boundary(loop, 1.0, 1e3), gm, 1e-6 * gm) << "trial " << trial;
    EXPECT_LT(simulate(loop, 0.95 * gm, loop.delay_ticks, 40000), 1e-3) << "trial " << trial;
    EXPECT_GT(simulate(loop, 1.05 * gm, loop.delay_ticks, 40000), 1.0) << "trial " << trial;
  }
  EXPECT_GE(checked, 15);
}

// Largest |θ_m| over the last tenth of a run of pid::Pid (gains × scale, output in N·m) on joint
// `joint` of robot::JointPlant, decoupled at a fixed inertia with the elastic gear, current loop
// and delay of `config`, reading the motor side as a drive does, from 0.05 rad at rest.
double simulate_on_plant(const fuzzypid::robot::RobotModel& model,
                         const fuzzypid::robot::PlantConfig& config, std::size_t joint,
                         const JointLoop& loop, double scale, int ticks) {
  fuzzypid::pid::Config<double> pc;
  pc.gains = {scale * loop.gains.kp, scale * loop.gains.ki, scale * loop.gains.kd};
  pc.derivative_filter_s = loop.derivative_filter_s;
  pc.derivative_source = loop.derivative;
  pc.anti_windup = fuzzypid::pid::AntiWindup::None;
  fuzzypid::pid::Pid<double> pid(pc);
  fuzzypid::robot::JointPlant plant(model, config);
  if (!plant.valid()) return NAN;
  fuzzypid::robot::JointVector q0 = fuzzypid::robot::kPaperStartJoints;
  q0[joint] += 0.05;
  plant.reset(q0, fuzzypid::robot::JointVector{});
  const double target = fuzzypid::robot::kPaperStartJoints[joint];
  double peak = 0.0;
  for (int k = 0; k < ticks; ++k) {
    fuzzypid::pid::Input<double> in;
    in.setpoint = target;
    in.measurement = plant.measured_position()[joint];
    in.measurement_rate = plant.measured_velocity()[joint];
    if (pid.update(in, loop.tick_s) != fuzzypid::Status::Ok) return INFINITY;
    fuzzypid::robot::JointVector tau{};
    tau[joint] = pid.output();
    if (plant.step(tau, loop.tick_s) != fuzzypid::robot::PlantStatus::Ok) return INFINITY;
    const double off = std::abs(plant.motor_position()[joint] - target);
    if (!(off < 1e3)) return INFINITY;
    if (k >= ticks - ticks / 10) peak = std::max(peak, off);
  }
  return peak;
}

// An elastic gear (JointLoop::gear_resonance_hz): over seeded random joints of the ER50-C20, ticks,
// resonances from below to above the Nyquist rate, damping ratios, current loops, delays of 0 to a
// tick and both derivative sources, the frequency response's gain margin is the state matrix's
// stability boundary, and robot::JointPlant run by pid::Pid (its own RK4 integration of the
// two-mass joint) is stable below it and diverges above it.
TEST(Margins, AnElasticGearIsModelledAsTheJointPlantRunsIt) {
  const std::uint64_t seed = 20261207;
  std::printf("seed %llu\n", static_cast<unsigned long long>(seed));
  std::mt19937_64 rng(seed);
  fuzzypid::support::UniformReal<double> unit(0.0, 1.0);
  const std::vector<fuzzypid::sim::Condition> conditions{fuzzypid::sim::Condition{}};
  std::string error;
  const auto experiments =
      fuzzypid::sim::ExperimentSet::create(conditions, fuzzypid::sim::ExperimentOptions{}, error);
  ASSERT_TRUE(experiments) << error;
  const fuzzypid::robot::RobotModel model = experiments->of(0).plant_model(conditions[0]);
  int checked = 0, away_from_nyquist = 0;
  for (int trial = 0; trial < 32; ++trial) {
    const auto joint = static_cast<std::size_t>(unit(rng) * 6.0) % 6;
    fuzzypid::robot::PlantConfig config;
    config.armature_kgm2 = fuzzypid::robot::kEr50ArmatureKgm2;
    config.inertia_update = fuzzypid::robot::InertiaUpdate::Fixed;
    config.torque_limit_nm = fuzzypid::robot::JointVector{1e9, 1e9, 1e9, 1e9, 1e9, 1e9};
    const double h = 0.01 * std::pow(5.0, unit(rng));                      // 10 .. 50 ms
    config.joint_resonance_hz[joint] = (0.5 + 2.5 * unit(rng)) * 0.5 / h;  // 0.5 .. 3 × Nyquist
    config.joint_damping_ratio = 0.1 * unit(rng);
    config.torque_bandwidth_hz = unit(rng) < 0.5 ? 0.0 : 20.0 + 80.0 * unit(rng);
    config.delay_s = h * std::floor(unit(rng) * 3.0) / 2.0;  // 0, h / 2 or h
    config.damping_nms[joint] = 5.0 * unit(rng);
    fuzzypid::robot::JointPlant probe(model, config);
    ASSERT_TRUE(probe.valid());
    probe.reset(fuzzypid::robot::kPaperStartJoints, fuzzypid::robot::JointVector{});
    const double j = probe.inertia()[joint], motor = config.armature_kgm2[joint];

    JointLoop loop;
    loop.tick_s = h;
    loop.plant_gain = 1.0 / j;  // the PID's output is the torque
    loop.damping_per_s = config.damping_nms[joint] / j;
    loop.torque_bandwidth_hz = config.torque_bandwidth_hz;
    fuzzypid::sim::set_delay(loop, config.delay_s);
    loop.gear_resonance_hz = config.joint_resonance_hz[joint];
    loop.gear_damping_ratio = config.joint_damping_ratio;
    loop.motor_inertia_fraction = motor / j;
    const double wb = (0.03 + 0.12 * unit(rng)) * M_PI / h;
    loop.gains = {j * wb * wb, j * 0.1 * wb * wb * wb, j * (1.0 + unit(rng)) * wb};
    loop.derivative_filter_s = 0.3 * unit(rng) * h;
    loop.derivative = unit(rng) < 0.5 ? DerivativeSource::Rates : DerivativeSource::Difference;
    const LoopMargins m = fuzzypid::sim::margins(loop);
    if (!m.stable || !std::isfinite(m.gain_margin_db)) continue;
    ++checked;
    if (std::abs(m.phase_crossover_rad_s - M_PI / h) > 1e-6 / h) ++away_from_nyquist;
    const double gm = std::pow(10.0, m.gain_margin_db / 20.0);
    // 1e-5: the bisections meet a lightly damped resonance's sharp phase there.
    EXPECT_NEAR(eigen_gain_boundary(loop, 1.0, 1e3), gm, 1e-5 * gm) << "trial " << trial;
    EXPECT_LT(simulate_on_plant(model, config, joint, loop, 0.95 * gm, 3000), 0.05)
        << "trial " << trial;
    EXPECT_GT(simulate_on_plant(model, config, joint, loop, 1.05 * gm, 3000), 0.5)
        << "trial " << trial;
  }
  EXPECT_GE(checked, 16);
  EXPECT_GE(away_from_nyquist, 4);
  std::printf("%d of 32 loops checked, %d crossing -180° away from the Nyquist rate\n", checked,
              away_from_nyquist);
}

// A gear far stiffer than the tick sees is the rigid joint; a soft one near the Nyquist rate is not.
TEST(Margins, AVeryStiffGearIsTheRigidJoint) {
  JointLoop rigid;
  rigid.tick_s = 0.05;
  rigid.plant_gain = 1.0;
  rigid.gains = {172.5, 0.00045, 21.35};
  rigid.torque_bandwidth_hz = 50.0;
  fuzzypid::sim::set_delay(rigid, 0.01);
  const LoopMargins r = fuzzypid::sim::margins(rigid);
  ASSERT_TRUE(r.stable);
  JointLoop stiff = rigid;
  stiff.gear_resonance_hz = 2000.0;  // 200 × the Nyquist rate
  stiff.gear_damping_ratio = 0.05;
  stiff.motor_inertia_fraction = 0.1;
  const LoopMargins s = fuzzypid::sim::margins(stiff);
  ASSERT_TRUE(s.stable);
  EXPECT_NEAR(s.gain_margin_db, r.gain_margin_db, 0.01);
  EXPECT_NEAR(s.phase_margin_deg, r.phase_margin_deg, 0.05);
  EXPECT_NEAR(s.disk_margin, r.disk_margin, 1e-3);
  JointLoop soft = stiff;
  soft.gear_resonance_hz = 9.0;
  EXPECT_FALSE(fuzzypid::sim::margins(soft).stable);
  // Invalid gears: a motor share outside (0, 1), a negative damping ratio.
  for (const double share : {0.0, 1.0, -0.2}) {
    JointLoop bad = stiff;
    bad.motor_inertia_fraction = share;
    EXPECT_FALSE(fuzzypid::sim::margins(bad).stable) << share;
  }
  JointLoop bad = stiff;
  bad.gear_damping_ratio = -0.1;
  EXPECT_FALSE(fuzzypid::sim::margins(bad).stable);
}

TEST(Margins, UnstableLoopHasNoDiskMargin) {
  JointLoop loop;
  loop.tick_s = 0.05;
  loop.gains = {4.0, 0.0, 100.0 * 0.05};  // Kd h = 0.25 ... times 10: beyond 2 / (Kd h)
  loop.gains.kd *= 10.0;
  const LoopMargins m = fuzzypid::sim::margins(loop);
  EXPECT_FALSE(m.stable);
  EXPECT_EQ(m.disk_margin, 0.0);
  EXPECT_LT(m.gain_margin_low_db, 0.0);
}

TEST(Margins, InvalidLoopIsUnstable) {
  JointLoop loop;
  loop.tick_s = 0.0;
  EXPECT_FALSE(fuzzypid::sim::margins(loop).stable);
  loop.tick_s = 0.01;
  loop.gains.kp = NAN;
  EXPECT_FALSE(fuzzypid::sim::margins(loop).stable);
}

// The ER50-C20's default condition (the section 6 line) with a shipped controller file.
struct Er50 {
  std::vector<fuzzypid::sim::Condition> conditions{fuzzypid::sim::Condition{}};
  std::optional<fuzzypid::sim::ExperimentSet> experiments;
  Er50() {
    std::string error;
    experiments =
        fuzzypid::sim::ExperimentSet::create(conditions, fuzzypid::sim::ExperimentOptions{}, error);
    EXPECT_TRUE(experiments) << error;
  }
  fuzzypid::sim::Certificate certify(const std::string& file, double delay_s = 0.0) const {
    fuzzypid::controller::ControllerSpec spec;
    fuzzypid::FileError err;
    EXPECT_TRUE(
        fuzzypid::controller_file::load(std::string(FUZZYPID_SOURCE_DIR) + "/" + file, spec, err))
        << err.to_string();
    fuzzypid::sim::CertifyOptions options;
    options.delay_s = delay_s;
    options.grid_points = 5;
    std::string error;
    const auto cert = fuzzypid::sim::certify(spec, conditions, *experiments, options, error);
    EXPECT_TRUE(cert) << error;
    return cert.value_or(fuzzypid::sim::Certificate{});
  }
};

TEST(Certify, Er50TunedPidGainMarginIsTheSimulatedBoundaryOfEachJoint) {
  const Er50 er50;
  const fuzzypid::sim::Certificate cert = er50.certify("tests/sim/data/drive_retune_pid.toml");
  EXPECT_TRUE(cert.certified);
  EXPECT_EQ(cert.verdict, "certified (linear, no saturation; gains may change every tick)");
  for (const auto& joint : cert.joints) {
    EXPECT_LE(joint.inertia_min_kgm2, joint.nominal_inertia_kgm2);
    EXPECT_GE(joint.inertia_max_kgm2, joint.nominal_inertia_kgm2);
    // The worst case's loop, simulated with pid::Pid: stable below its margin (small and still
    // shrinking: a small Ki leaves a pole near 1 that decays over thousands of ticks), divergent
    // above.
    const auto decays = [](const JointLoop& loop, double scale, int delay_ticks) {
      const double late = simulate(loop, scale, delay_ticks, 40000);
      return late < 1e-4 && late < 0.5 * simulate(loop, scale, delay_ticks, 20000);
    };
    const fuzzypid::sim::MarginCase& w = joint.worst_gain;
    const double gm = std::pow(10.0, w.margins.gain_margin_db / 20.0);
    EXPECT_TRUE(decays(w.loop, 0.95 * gm, 0));
    EXPECT_GT(simulate(w.loop, 1.05 * gm, 0, 20000), 1.0);
    // And with its whole-tick delay margin.
    const int ticks = joint.worst_delay.margins.delay_margin_ticks;
    ASSERT_GE(ticks, 1);
    EXPECT_TRUE(decays(joint.worst_delay.loop, 1.0, ticks - 1));
    EXPECT_GT(simulate(joint.worst_delay.loop, 1.0, ticks, 20000), 1.0);
  }
}

// A 10 Hz gear (the tick's Nyquist rate) behind a 30 Hz current loop: the tuned PID's joint 1
// is unstable there with no delay and stable behind a whole tick. In a set whose largest delay is
// a tick (another, rigid condition's), the gear is still checked at its own condition's delay.
TEST(Certify, AGearIsCheckedAtItsOwnConditionsDelay) {
  Er50 er50;
  fuzzypid::sim::Condition rigid_late, geared;
  rigid_late.effects.delay_s = 0.05;
  geared.effects.torque_bandwidth_hz = 30.0;
  geared.effects.joint_resonance_hz.fill(10.0);
  geared.effects.joint_damping_ratio = 0.05;
  er50.conditions = {rigid_late, geared};
  std::string error;
  er50.experiments = fuzzypid::sim::ExperimentSet::create(
      er50.conditions, fuzzypid::sim::ExperimentOptions{}, error);
  ASSERT_TRUE(er50.experiments) << error;
  const fuzzypid::sim::Certificate cert =
      er50.certify("tests/sim/data/drive_retune_pid.toml", 0.05);
  EXPECT_FALSE(cert.certified);
  const fuzzypid::sim::JointCertificate& joint1 = cert.joints[0];
  EXPECT_FALSE(joint1.stable);
  EXPECT_EQ(joint1.worst_disk.margins.disk_margin, 0.0);
  EXPECT_EQ(joint1.worst_disk.loop.delay_ticks, 0);
  EXPECT_EQ(joint1.worst_disk.loop.delay_fraction, 0.0);
  EXPECT_GT(joint1.worst_disk.loop.gear_resonance_hz, 9.5);
  EXPECT_LT(joint1.worst_disk.loop.gear_resonance_hz, 10.5);
  // Behind the whole tick alone the same gear is stable: the set's largest delay would hide it.
  er50.conditions = {geared};
  er50.conditions[0].effects.delay_s = 0.05;
  er50.experiments = fuzzypid::sim::ExperimentSet::create(
      er50.conditions, fuzzypid::sim::ExperimentOptions{}, error);
  ASSERT_TRUE(er50.experiments) << error;
  EXPECT_TRUE(er50.certify("tests/sim/data/drive_retune_pid.toml", 0.05).joints[0].stable);
}

// A bandwidth scale per joint: each joint is certified with the gains and derivative filter it
// runs, the same as a uniform controller whose gains are that joint's.
TEST(Certify, AJointWithABandwidthScaleIsCertifiedAsTheUniformControllerWithItsGains) {
  const Er50 er50;
  for (const char* name : {"per_joint_pid.toml", "per_joint_scheduled.toml"}) {
    const std::string file = std::string("tests/sim/data/") + name;
    const fuzzypid::sim::Certificate scaled = er50.certify(file);
    fuzzypid::controller::ControllerSpec spec;
    fuzzypid::FileError err;
    ASSERT_TRUE(
        fuzzypid::controller_file::load(std::string(FUZZYPID_SOURCE_DIR) + "/" + file, spec, err));
    for (std::size_t i = 0; i < 6; ++i) {
      fuzzypid::controller::ControllerSpec uniform = spec;
      const double s = spec.bandwidth_scale[i];
      uniform.bandwidth_scale = fuzzypid::controller::kUniformBandwidth;
      uniform.gains = {spec.gains.kp * s * s, spec.gains.ki * s * s * s, spec.gains.kd * s};
      uniform.gain_max = {spec.gain_max.kp * s * s, spec.gain_max.ki * s * s * s,
                          spec.gain_max.kd * s};
      uniform.pid.derivative_filter_s = spec.pid.derivative_filter_s / s;
      fuzzypid::sim::CertifyOptions options;
      options.grid_points = 5;
      std::string error;
      const auto same =
          fuzzypid::sim::certify(uniform, er50.conditions, *er50.experiments, options, error);
      ASSERT_TRUE(same) << error;
      const auto& a = scaled.joints[i].worst_disk.margins;
      const auto& b = same->joints[i].worst_disk.margins;
      EXPECT_NEAR(a.disk_margin, b.disk_margin, 1e-9) << name << " joint " << i + 1;
      EXPECT_NEAR(a.phase_margin_deg, b.phase_margin_deg, 1e-7) << name << " joint " << i + 1;
      EXPECT_EQ(scaled.joints[i].stable, same->joints[i].stable);
    }
    // The scales matter: joint 6 (s = 0.5) and joint 5 (s = 3) differ from joint 1's loop.
    EXPECT_GT(std::fabs(scaled.joints[4].worst_disk.margins.disk_margin -
                        scaled.joints[5].worst_disk.margins.disk_margin),
              0.01)
        << name;
  }
}

// The tuner screens each candidate with its joints on several threads: a certificate does not
// depend on the order or the threads its joints are computed on.
TEST(Certify, ItsJointsComputedInAnyOrderOrOnThreadsGiveTheSameCertificate) {
  const Er50 er50;
  fuzzypid::controller::ControllerSpec spec;
  fuzzypid::FileError err;
  ASSERT_TRUE(fuzzypid::controller_file::load(
      std::string(FUZZYPID_SOURCE_DIR) + "/tests/sim/data/per_joint_scheduled.toml", spec, err))
      << err.to_string();
  const auto expect_same = [](const fuzzypid::sim::Certificate& a,
                              const fuzzypid::sim::Certificate& b, const char* how) {
    EXPECT_EQ(a.verdict, b.verdict) << how;
    EXPECT_EQ(a.certified, b.certified) << how;
    for (std::size_t i = 0; i < 6; ++i) {
      const auto& x = a.joints[i];
      const auto& y = b.joints[i];
      EXPECT_EQ(x.stable, y.stable) << how << " joint " << i + 1;
      EXPECT_EQ(x.cases, y.cases) << how << " joint " << i + 1;
      EXPECT_EQ(x.worst_disk.margins.disk_margin, y.worst_disk.margins.disk_margin) << how;
      EXPECT_EQ(x.worst_gain.margins.gain_margin_db, y.worst_gain.margins.gain_margin_db) << how;
      EXPECT_EQ(x.worst_phase.margins.phase_margin_deg, y.worst_phase.margins.phase_margin_deg)
          << how;
      EXPECT_EQ(x.worst_delay.margins.delay_margin_s, y.worst_delay.margins.delay_margin_s) << how;
      EXPECT_EQ(x.worst_disk.inertia_kgm2, y.worst_disk.inertia_kgm2) << how;
      EXPECT_EQ(x.lyapunov.certified, y.lyapunov.certified) << how;
      EXPECT_EQ(x.lyapunov.reason, y.lyapunov.reason) << how;
      EXPECT_TRUE(x.lyapunov.contraction == y.lyapunov.contraction ||
                  (std::isnan(x.lyapunov.contraction) && std::isnan(y.lyapunov.contraction)))
          << how;
    }
  };
  for (const bool lyapunov : {true, false}) {
    fuzzypid::sim::CertifyOptions options;
    options.grid_points = 5;
    options.delay_s = 0.03;
    options.lyapunov = lyapunov;
    std::string error;
    const auto in_order =
        fuzzypid::sim::certify(spec, er50.conditions, *er50.experiments, options, error);
    ASSERT_TRUE(in_order) << error;
    ASSERT_GT(in_order->joints[0].cases, 1u);
    options.for_each_joint = [](std::size_t n, const std::function<void(std::size_t)>& joint) {
      for (std::size_t i = n; i-- > 0;)
        joint(i);
    };
    const auto reversed =
        fuzzypid::sim::certify(spec, er50.conditions, *er50.experiments, options, error);
    ASSERT_TRUE(reversed) << error;
    expect_same(*in_order, *reversed, lyapunov ? "reversed, Lyapunov" : "reversed");
    if (lyapunov) continue;  // the SDPA solver is not run on several threads at once
    options.for_each_joint = [](std::size_t n, const std::function<void(std::size_t)>& joint) {
      std::vector<std::thread> threads;
      for (std::size_t i = 0; i < n; ++i)
        threads.emplace_back([&joint, i] { joint(i); });
      for (std::thread& t : threads)
        t.join();
    };
    const auto threaded =
        fuzzypid::sim::certify(spec, er50.conditions, *er50.experiments, options, error);
    ASSERT_TRUE(threaded) << error;
    expect_same(*in_order, *threaded, "a thread per joint");
  }
}

TEST(Certify, AGainScheduleIsCertifiedOverTheBoxOfTheGainsItProduces) {
  const Er50 er50;
  const fuzzypid::sim::Certificate cert = er50.certify("tests/sim/data/certified_schedule.toml");
  EXPECT_TRUE(cert.moving_gains);
  EXPECT_TRUE(cert.certified) << cert.verdict;
  EXPECT_EQ(cert.verdict, "certified (linear, no saturation; gains may change every tick)");
  for (const auto& joint : cert.joints) {
    EXPECT_GT(joint.gain_triples, 1u);
    // The box spans the triples the supervisor produced: the worst frozen cases lie inside it.
    const fuzzypid::sim::GainBox& box = joint.gain_box;
    EXPECT_LT(box.low.kp, box.high.kp);
    for (const fuzzypid::sim::MarginCase* c : {&joint.worst_gain, &joint.worst_disk}) {
      EXPECT_GE(c->gains.kp, box.low.kp);
      EXPECT_LE(c->gains.kp, box.high.kp);
      EXPECT_GE(c->gains.kd, box.low.kd);
      EXPECT_LE(c->gains.kd, box.high.kd);
    }
    EXPECT_TRUE(joint.lyapunov.certified) << joint.lyapunov.reason;
    EXPECT_LT(joint.lyapunov.contraction, 1.0);
  }
}

TEST(Certify, APaperFuzzyPidWhoseKiReachesZeroIsNotCertified) {
  const Er50 er50;
  const fuzzypid::sim::Certificate cert = er50.certify("controllers/paper_fuzzy.toml");
  EXPECT_TRUE(cert.moving_gains);
  EXPECT_FALSE(cert.certified);
  EXPECT_EQ(cert.joints[0].gain_box.low.ki, 0.0);
  EXPECT_EQ(cert.verdict,
            "not certified (joint 1: Ki reaches 0 inside the box: there the integral is frozen and "
            "holds its value)");
}

TEST(Certify, DelayBeyondTheDelayMarginIsNotCertifiedAndIsDeterministic) {
  const Er50 er50;
  const fuzzypid::sim::Certificate a = er50.certify("tests/sim/data/drive_retune_pid.toml");
  const fuzzypid::sim::Certificate b = er50.certify("tests/sim/data/drive_retune_pid.toml");
  for (std::size_t i = 0; i < a.joints.size(); ++i) {
    EXPECT_EQ(a.joints[i].worst_disk.margins.disk_margin,
              b.joints[i].worst_disk.margins.disk_margin);
    EXPECT_EQ(a.joints[i].worst_gain.margins.gain_margin_db,
              b.joints[i].worst_gain.margins.gain_margin_db);
  }
  // 5 ms beyond the smallest exact delay margin of its joints.
  double margin_s = INFINITY;
  for (const auto& joint : a.joints)
    margin_s = std::min(margin_s, joint.worst_delay.margins.delay_margin_exact_s);
  ASSERT_TRUE(std::isfinite(margin_s));
  const fuzzypid::sim::Certificate late =
      er50.certify("tests/sim/data/drive_retune_pid.toml", margin_s + 0.005);
  EXPECT_FALSE(late.certified);
  EXPECT_EQ(late.verdict, "not certified (unstable at frozen gains)");
}

TEST(Certify, AFractionalDelayUsesUpTheExactDelayMargin) {
  const Er50 er50;
  const fuzzypid::sim::Certificate a = er50.certify("tests/sim/data/drive_retune_pid.toml");
  const fuzzypid::sim::Certificate b = er50.certify("tests/sim/data/drive_retune_pid.toml", 0.012);
  EXPECT_TRUE(b.certified);
  for (std::size_t i = 0; i < a.joints.size(); ++i)
    EXPECT_NEAR(a.joints[i].worst_delay.margins.delay_margin_exact_s - 0.012,
                b.joints[i].worst_delay.margins.delay_margin_exact_s, 1e-9);
  fuzzypid::controller::ControllerSpec spec;
  fuzzypid::sim::CertifyOptions options;
  options.delay_s = -0.001;
  std::string error;
  EXPECT_FALSE(fuzzypid::sim::certify(spec, er50.conditions, *er50.experiments, options, error));
  EXPECT_EQ(error, "the delay must be finite and >= 0");
}

}  // namespace
