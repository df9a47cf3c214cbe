// The certificate for gains that change every tick (sim/lyapunov.hpp), against an independent
// simulation: the library's pid::Pid on a joint stepped exactly (zero-order hold, a current loop
// integrated with fine RK4 steps), its gains and plant gain redrawn on every tick.
#include "fuzzypid/sim/lyapunov.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <random>
#include <vector>

#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid/pid/pid.hpp"
#include "fuzzypid/sim/certify.hpp"
#include "fuzzypid/sim/experiment.hpp"
#include "fuzzypid/sim/margins.hpp"
#include "fuzzypid_support/uniform_real.hpp"

namespace {

using fuzzypid::pid::Gains;
using fuzzypid::sim::GainBox;
using fuzzypid::sim::LyapunovCertificate;
using fuzzypid::sim::SwitchingLoop;

// A uniform double in [0, 1), the same draws on every standard library.
double unit(std::mt19937_64& rng) {
  return fuzzypid::support::UniformReal<double>(0.0, 1.0)(rng);
}

// One sequence's gains and plant gain on every tick.
struct Tick {
  Gains<double> gains;
  double plant_gain;
};

// The joint θ̈ = c v, v̇ = w (u_delayed − v) (v = u_delayed when w = 0), u from pid::Pid with this
// tick's gains (regulation to 0 from θ = 0.05 rad at rest), u reaching the joint `delay_ticks`
// ticks late. Returns the largest |θ| over the run (inf once it leaves 1e6 rad).
double run(const SwitchingLoop& set, const std::vector<Tick>& ticks) {
  fuzzypid::pid::Config<double> config;
  config.derivative_filter_s = set.loop.derivative_filter_s;
  config.derivative_source = set.loop.derivative;
  config.anti_windup = fuzzypid::pid::AntiWindup::None;
  fuzzypid::pid::Pid<double> pid(config);
  const double h = set.loop.tick_s;
  const double w = 2.0 * 3.14159265358979323846 * set.torque_bandwidth_min_hz;
  double theta = 0.05, omega = 0.0, v = 0.0, peak = 0.0;
  std::deque<double> line(static_cast<std::size_t>(set.loop.delay_ticks), 0.0);
  for (const Tick& t : ticks) {
    fuzzypid::pid::Input<double> in;
    in.measurement = theta;
    in.measurement_rate = omega;
    if (pid.update(in, h, t.gains) != fuzzypid::Status::Ok) return INFINITY;
    line.push_back(pid.output());
    const double u = line.front();
    line.pop_front();
    const double c = t.plant_gain;
    if (w == 0.0) {
      theta += omega * h + 0.5 * c * u * h * h;
      omega += c * u * h;
    } else {
      // RK4 with 200 steps per tick: independent of the matrix exponential under test.
      const int n = 200;
      const double s = h / n;
      const auto f = [&](double, double om, double vv, double& d_th, double& d_om, double& d_v) {
        d_th = om;
        d_om = c * vv;
        d_v = w * (u - vv);
      };
      for (int k = 0; k < n; ++k) {
        double a1, b1, c1, a2, b2, c2, a3, b3, c3, a4, b4, c4;
        f(theta, omega, v, a1, b1, c1);
        f(theta + 0.5 * s * a1, omega + 0.5 * s * b1, v + 0.5 * s * c1, a2, b2, c2);
        f(theta + 0.5 * s * a2, omega + 0.5 * s * b2, v + 0.5 * s * c2, a3, b3, c3);
        f(theta + s * a3, omega + s * b3, v + s * c3, a4, b4, c4);
        theta += s / 6.0 * (a1 + 2 * a2 + 2 * a3 + a4);
        omega += s / 6.0 * (b1 + 2 * b2 + 2 * b3 + b4);
        v += s / 6.0 * (c1 + 2 * c2 + 2 * c3 + c4);
      }
    }
    if (!(std::abs(theta) < 1e6)) return INFINITY;
    peak = std::max(peak, std::abs(theta));
  }
  return peak;
}

// A random sequence inside the box: every tick each gain is a corner (half the time) or a
// uniform draw, the plant gain likewise within [c_min, c_max].
std::vector<Tick> random_sequence(const SwitchingLoop& set, std::size_t n, std::mt19937_64& rng) {
  const auto pick = [&](double lo, double hi) {
    if (unit(rng) < 0.5) return unit(rng) < 0.5 ? lo : hi;
    return lo + (hi - lo) * unit(rng);
  };
  const GainBox& b = set.gains;
  std::vector<Tick> out(n);
  for (Tick& t : out) {
    t.gains = {pick(b.low.kp, b.high.kp), pick(b.low.ki, b.high.ki), pick(b.low.kd, b.high.kd)};
    t.plant_gain = pick(set.plant_gain_min, set.plant_gain_max);
  }
  return out;
}

// A PID on a double integrator at 10 ms, its gains anywhere in a box and the inertia anywhere in
// a factor-2 range (J^ / J in [0.7, 1.4]).
SwitchingLoop pid_box() {
  SwitchingLoop s;
  s.loop.tick_s = 0.01;
  s.gains.low = {20.0, 2.0, 6.0};
  s.gains.high = {40.0, 8.0, 10.0};
  s.plant_gain_min = 0.7;
  s.plant_gain_max = 1.4;
  return s;
}

// A PD on a double integrator at 200 ms, Kp switching between 1 and 15 (Kd = 2 s): each corner
// stable on its own (spectral radii 0.854 and 0.949), switching between them is not.
SwitchingLoop pumping_box() {
  SwitchingLoop s;
  s.loop.tick_s = 0.2;
  s.gains.low = {1.0, 0.0, 2.0};
  s.gains.high = {15.0, 0.0, 2.0};
  s.plant_gain_min = s.plant_gain_max = 1.0;
  return s;
}

TEST(CommonLyapunov, AFixedStableLoopIsCertifiedWithAContractionNoBelowItsSpectralRadius) {
  SwitchingLoop s = pid_box();
  s.gains.high = s.gains.low;
  s.plant_gain_max = s.plant_gain_min;
  const LyapunovCertificate c = fuzzypid::sim::common_lyapunov(s);
  ASSERT_TRUE(c.certified) << c.reason;
  EXPECT_EQ(c.inertia_intervals, 1u);
  EXPECT_EQ(c.vertices, 1u);
  EXPECT_EQ(c.states, 5u);
  fuzzypid::sim::JointLoop frozen = s.loop;
  frozen.gains = s.gains.low;
  frozen.plant_gain = s.plant_gain_min;
  const double rho = fuzzypid::sim::closed_loop_spectral_radius(frozen);
  // ‖A‖_P >= ρ(A) for any P: the reported contraction cannot beat the eigenvalues.
  EXPECT_GE(c.contraction, rho - 1e-12);
  EXPECT_LT(c.contraction, 1.0);
  EXPECT_TRUE(c.reason.empty());
}

// The certificate is of rigid joints (its state matrix is affine in c only without a gear): a
// loop with an elastic gear is refused with the reason, though the same rigid box is certified.
TEST(CommonLyapunov, ALoopWithAnElasticGearIsRefused) {
  SwitchingLoop s = pid_box();
  ASSERT_TRUE(fuzzypid::sim::common_lyapunov(s).certified);
  s.loop.gear_resonance_hz = 40.0;
  s.loop.gear_damping_ratio = 0.05;
  s.loop.motor_inertia_fraction = 0.3;
  const LyapunovCertificate c = fuzzypid::sim::common_lyapunov(s);
  EXPECT_FALSE(c.certified);
  EXPECT_EQ(c.reason, "an elastic gear (the certificate is of rigid joints)");
}

TEST(CommonLyapunov, ACertifiedBoxNeverDivergesUnderTenThousandRandomSwitchingSequences) {
  const SwitchingLoop s = pid_box();
  const LyapunovCertificate c = fuzzypid::sim::common_lyapunov(s);
  ASSERT_TRUE(c.certified) << c.reason;
  EXPECT_EQ(c.inertia_intervals, 1u);  // the inertia may switch every tick too
  const std::uint64_t seed = 20261204;
  std::printf("seed %llu\n", static_cast<unsigned long long>(seed));
  std::mt19937_64 rng(seed);
  double worst = 0.0;
  for (int k = 0; k < 10000; ++k)
    worst = std::max(worst, run(s, random_sequence(s, 400, rng)));
  // V = xᵀPx never grows: |θ| stays within a small factor of its start (0.05 rad).
  EXPECT_LT(worst, 0.5);
}

// The shipped tuned gain schedule on the ER50's default condition: certify's box for joint 2 (its
// gains over the (Ke e, Kec ec) grid) and its plant-gain range J^ / J, certified, and 10,000
// random sequences of gains and inertias inside them never diverge.
TEST(CommonLyapunov, TheCertifiedTunedScheduleNeverDivergesUnderRandomSwitchingInItsBox) {
  fuzzypid::controller::ControllerSpec spec;
  fuzzypid::FileError err;
  ASSERT_TRUE(fuzzypid::controller_file::load(
      std::string(FUZZYPID_SOURCE_DIR) + "/tests/sim/data/certified_schedule.toml", spec, err))
      << err.to_string();
  const std::vector<fuzzypid::sim::Condition> conditions{fuzzypid::sim::Condition{}};
  std::string error;
  const auto experiments =
      fuzzypid::sim::ExperimentSet::create(conditions, fuzzypid::sim::ExperimentOptions{}, error);
  ASSERT_TRUE(experiments) << error;
  fuzzypid::sim::CertifyOptions options;
  options.grid_points = 5;
  const auto cert = fuzzypid::sim::certify(spec, conditions, *experiments, options, error);
  ASSERT_TRUE(cert) << error;
  ASSERT_TRUE(cert->certified) << cert->verdict;
  const fuzzypid::sim::JointCertificate& j = cert->joints[1];
  SwitchingLoop s;
  s.loop.tick_s = spec.units.tick_s;
  s.loop.derivative_filter_s = spec.pid.derivative_filter_s;
  s.loop.derivative = spec.pid.derivative;
  s.gains = j.gain_box;
  s.plant_gain_min = j.nominal_inertia_kgm2 / j.inertia_max_kgm2;
  s.plant_gain_max = j.nominal_inertia_kgm2 / j.inertia_min_kgm2;
  EXPECT_LT(s.gains.low.kp, s.gains.high.kp);  // the gains do move
  EXPECT_TRUE(fuzzypid::sim::common_lyapunov(s).certified);
  std::mt19937_64 rng(20261205);
  double worst = 0.0;
  for (int k = 0; k < 10000; ++k)
    worst = std::max(worst, run(s, random_sequence(s, 200, rng)));
  EXPECT_LT(worst, 0.5);
}

TEST(CommonLyapunov, ABoxThatSwitchingDestabilisesIsRefusedAndHasADivergingSequence) {
  const SwitchingLoop s = pumping_box();
  for (const Gains<double>& g : {s.gains.low, s.gains.high}) {
    fuzzypid::sim::JointLoop frozen = s.loop;
    frozen.gains = g;
    frozen.plant_gain = 1.0;
    EXPECT_LT(fuzzypid::sim::closed_loop_spectral_radius(frozen), 1.0);  // each corner stable
  }
  const LyapunovCertificate c = fuzzypid::sim::common_lyapunov(s);
  EXPECT_FALSE(c.certified);
  EXPECT_GE(c.switching_radius, 1.0);
  EXPECT_EQ(c.switching_period, 5u);
  EXPECT_NE(c.reason.find("with period 5 diverges"), std::string::npos) << c.reason;
  // Independently: some periodic switching of period 5 between the two corners diverges in the
  // simulated joint, which a frozen corner never does.
  bool diverged = false;
  for (unsigned pattern = 0; pattern < 32 && !diverged; ++pattern) {
    std::vector<Tick> ticks;
    ticks.reserve(500);
    for (int k = 0; k < 500; ++k)
      ticks.push_back({(pattern >> (k % 5)) & 1u ? s.gains.high : s.gains.low, 1.0});
    diverged = !(run(s, ticks) < 1e3);
  }
  EXPECT_TRUE(diverged);
  for (const Gains<double>& g : {s.gains.low, s.gains.high})
    EXPECT_LT(run(s, std::vector<Tick>(500, Tick{g, 1.0})), 0.1);
}

TEST(CommonLyapunov, ACertifiedBoxWithDelayAndACurrentLoopNeverDivergesUnderRandomSwitching) {
  SwitchingLoop s = pid_box();
  s.loop.delay_ticks = 1;
  s.loop.derivative_filter_s = 0.005;
  s.torque_bandwidth_min_hz = s.torque_bandwidth_max_hz = 50.0;
  const LyapunovCertificate c = fuzzypid::sim::common_lyapunov(s);
  ASSERT_TRUE(c.certified) << c.reason;
  EXPECT_EQ(c.states, 7u);  // θ, θ̇, v, I, d, θ_prev, one command on its way
  std::mt19937_64 rng(7);
  double worst = 0.0;
  for (int k = 0; k < 300; ++k)
    worst = std::max(worst, run(s, random_sequence(s, 300, rng)));
  EXPECT_LT(worst, 0.5);
  // The same box at a 1 Hz current loop: a corner is unstable, and the certificate says so.
  s.torque_bandwidth_min_hz = s.torque_bandwidth_max_hz = 1.0;
  const LyapunovCertificate slow = fuzzypid::sim::common_lyapunov(s);
  EXPECT_FALSE(slow.certified);
  EXPECT_NE(slow.reason.find("unstable with its gains frozen"), std::string::npos) << slow.reason;
}

TEST(Margins, WithACurrentLoopTheGainMarginIsTheSimulatedBoundary) {
  SwitchingLoop s = pid_box();
  s.torque_bandwidth_min_hz = s.torque_bandwidth_max_hz = 20.0;
  fuzzypid::sim::JointLoop loop = s.loop;
  loop.gains = s.gains.low;
  loop.torque_bandwidth_hz = 20.0;
  const fuzzypid::sim::LoopMargins m = fuzzypid::sim::margins(loop);
  ASSERT_TRUE(m.stable);
  const double gm = std::pow(10.0, m.gain_margin_db / 20.0);
  ASSERT_TRUE(std::isfinite(gm));
  const auto scaled = [&](double k) {
    const Gains<double> g{k * loop.gains.kp, k * loop.gains.ki, k * loop.gains.kd};
    return run(s, std::vector<Tick>(3000, Tick{g, 1.0}));
  };
  EXPECT_LT(scaled(0.95 * gm), 0.1);
  EXPECT_FALSE(scaled(1.05 * gm) < 1e3);
  // A current loop far faster than the tick is no current loop.
  loop.torque_bandwidth_hz = 1e5;
  fuzzypid::sim::JointLoop ideal = loop;
  ideal.torque_bandwidth_hz = 0.0;
  EXPECT_NEAR(fuzzypid::sim::margins(loop).gain_margin_db,
              fuzzypid::sim::margins(ideal).gain_margin_db, 1e-2);
  EXPECT_NEAR(fuzzypid::sim::margins(loop).phase_margin_deg,
              fuzzypid::sim::margins(ideal).phase_margin_deg, 1e-2);
}

TEST(CommonLyapunov, AWideInertiaRangeIsCertifiedInIntervalsWhenNoSinglePCoversIt) {
  SwitchingLoop s = pid_box();
  s.plant_gain_min = 0.5;
  s.plant_gain_max = 2.0;
  const LyapunovCertificate c = fuzzypid::sim::common_lyapunov(s);
  ASSERT_TRUE(c.certified) << c.reason;
  EXPECT_GT(c.inertia_intervals, 1u);
}

TEST(CommonLyapunov, AKiThatReachesZeroAndInvalidRangesAreRefusedWithTheReason) {
  SwitchingLoop s = pid_box();
  s.gains.low.ki = 0.0;
  const LyapunovCertificate zero = fuzzypid::sim::common_lyapunov(s);
  EXPECT_FALSE(zero.certified);
  EXPECT_NE(zero.reason.find("Ki reaches 0"), std::string::npos);
  for (double bad : {std::nan(""), HUGE_VAL, -1.0, 0.0}) {
    SwitchingLoop b = pid_box();
    b.plant_gain_min = bad;
    EXPECT_EQ(fuzzypid::sim::common_lyapunov(b).reason, "invalid loop or ranges") << bad;
  }
  SwitchingLoop reversed = pid_box();
  std::swap(reversed.gains.low, reversed.gains.high);
  EXPECT_EQ(fuzzypid::sim::common_lyapunov(reversed).reason, "invalid loop or ranges");
}

TEST(CommonLyapunov, IsDeterministic) {
  const LyapunovCertificate a = fuzzypid::sim::common_lyapunov(pid_box());
  const LyapunovCertificate b = fuzzypid::sim::common_lyapunov(pid_box());
  EXPECT_EQ(a.certified, b.certified);
  EXPECT_EQ(a.contraction, b.contraction);
  EXPECT_EQ(a.condition_number, b.condition_number);
}

}  // namespace
