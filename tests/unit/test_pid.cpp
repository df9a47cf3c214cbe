// pid::Pid (Eq. 2): closed-loop responses on a double integrator, anti-windup, online gain
// changes, derivative kick and filter, feed-forward, bumpless start, and fault handling.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>
#include <random>
#include <string>

#include "fuzzypid/pid/pid.hpp"
#include "fuzzypid_support/uniform_real.hpp"

namespace {

using fuzzypid::Status;
using fuzzypid::pid::AntiWindup;
using fuzzypid::pid::DerivativeOn;
using fuzzypid::pid::DerivativeSource;
using Pid = fuzzypid::pid::Pid<double>;
using Config = fuzzypid::pid::Config<double>;
using Input = fuzzypid::pid::Input<double>;
using Gains = fuzzypid::pid::Gains<double>;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// One joint J theta'' = u with u held constant over each tick (zero-order hold), integrated
// exactly: theta += dt omega + dt^2 u / (2 J), omega += dt u / J.
struct DoubleIntegrator {
  double inertia;
  double position = 0.0;
  double velocity = 0.0;
  void step(double u, double dt) {
    position += dt * velocity + dt * dt * u / (2.0 * inertia);
    velocity += dt * u / inertia;
  }
};

Input at(double setpoint, double measurement, double measurement_rate = 0.0) {
  Input in;
  in.setpoint = setpoint;
  in.measurement = measurement;
  in.measurement_rate = measurement_rate;
  return in;
}

Config gains_only(double kp, double ki, double kd) {
  Config c;
  c.gains = {kp, ki, kd};
  return c;
}

// Position error z_k = theta_k - r of the closed loop z_{k+1} = M z_k, in closed form:
// M^k = (l1^k (M - l2 I) - l2^k (M - l1 I)) / (l1 - l2) for the eigenvalues l1 != l2 of M.
double closed_form_error(const std::array<std::array<double, 2>, 2>& m, double z0, double v0,
                         int k) {
  using C = std::complex<double>;
  const double trace = m[0][0] + m[1][1];
  const double det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
  const C root = std::sqrt(C(trace * trace / 4.0 - det));
  const C l1 = trace / 2.0 + root;
  const C l2 = trace / 2.0 - root;
  const C p1 = std::pow(l1, k);
  const C p2 = std::pow(l2, k);
  const C m00 = (p1 * (m[0][0] - l2) - p2 * (m[0][0] - l1)) / (l1 - l2);
  const C m01 = (p1 - p2) * m[0][1] / (l1 - l2);
  return (m00 * z0 + m01 * v0).real();
}

struct PdCase {
  double inertia, kp, kd, dt;
};

TEST(Pid, PdOnADoubleIntegratorFollowsTheExactDiscreteClosedLoop) {
  // u_k = Kp (r - theta_k) + Kd (0 - omega_k) with DerivativeSource::Rates and the measured
  // velocity; the plant sampled with ZOH gives x_{k+1} = (A - B K) x_k + B Kp r.
  const PdCase cases[] = {
      {1.0, 4.0, 0.0, 0.05},     // P only: a marginally unstable oscillation under ZOH
      {2.0, 4.0, 3.0, 0.05},     // underdamped
      {0.5, 4.0, 2.0, 0.01},     // well damped
      {10.0, 4.0, 100.0, 0.05},  // the paper's Kp, Kd on a heavy joint: slow pole ~ -Kp/Kd
  };
  for (const DerivativeOn on : {DerivativeOn::Error, DerivativeOn::Measurement}) {
    for (const auto& c : cases) {
      SCOPED_TRACE("J=" + std::to_string(c.inertia) + " Kp=" + std::to_string(c.kp) +
                   " Kd=" + std::to_string(c.kd) + " dt=" + std::to_string(c.dt));
      Config config = gains_only(c.kp, 0.0, c.kd);
      config.derivative_on = on;
      Pid pid(config);
      DoubleIntegrator plant{c.inertia};
      const double r = 0.1;
      const double b0 = c.dt * c.dt / (2.0 * c.inertia);
      const double b1 = c.dt / c.inertia;
      const std::array<std::array<double, 2>, 2> m{
          {{{1.0 - b0 * c.kp, c.dt - b0 * c.kd}}, {{-b1 * c.kp, 1.0 - b1 * c.kd}}}};
      for (int k = 0; k <= 400; ++k) {
        const double expected = r + closed_form_error(m, -r, 0.0, k);
        ASSERT_NEAR(plant.position, expected, 1e-12) << "tick " << k;
        ASSERT_EQ(pid.update(at(r, plant.position, plant.velocity), c.dt), Status::Ok);
        ASSERT_NEAR(pid.terms().d, -c.kd * plant.velocity, 1e-15);
        plant.step(pid.output(), c.dt);
      }
    }
  }
}

TEST(Pid, POnlyStepOnADoubleIntegratorMatchesTheContinuousSolutionWithinTheZohBound) {
  // Continuous loop: J theta'' = Kp (r - theta), theta(0) = theta'(0) = 0, so
  // theta(t) = r (1 - cos(w t)), w = sqrt(Kp / J).
  // The sampled loop is the continuous one plus a disturbance d(t) = Kp (theta(t) - theta(t_k)),
  // |d| <= Kp dt v_max with v_max = max |theta'| (velocity is piecewise linear, so its sampled
  // maximum is its maximum). The deviation obeys J eps'' + Kp eps = d, eps(0) = eps'(0) = 0, so
  // eps(t) = int_0^t sin(w (t - s)) d(s) / (J w) ds and |eps(t)| <= t w dt v_max.
  const double inertia = 1.0;
  const double kp = 4.0;  // the paper's Kp
  const double dt = 1e-3;
  const double r = 0.1;
  const double w = std::sqrt(kp / inertia);
  Pid pid(gains_only(kp, 0.0, 0.0));
  DoubleIntegrator plant{inertia};
  double v_max = 0.0;
  double worst_ratio = 0.0;
  for (int k = 0; k <= 5000; ++k) {
    const double t = k * dt;
    v_max = std::max(v_max, std::fabs(plant.velocity));
    const double bound = t * w * dt * v_max + 1e-12;
    const double deviation = std::fabs(plant.position - r * (1.0 - std::cos(w * t)));
    ASSERT_LE(deviation, bound) << "t = " << t;
    worst_ratio = std::max(worst_ratio, deviation / bound);
    ASSERT_EQ(pid.update(at(r, plant.position, plant.velocity), dt), Status::Ok);
    ASSERT_EQ(pid.output(), kp * (r - plant.position));
    plant.step(pid.output(), dt);
  }
  RecordProperty("worst_deviation_over_bound", std::to_string(worst_ratio));
}

TEST(Pid, IntegratesKiTimesErrorTimesDt) {
  Pid pid(gains_only(0.0, 2.0, 0.0));
  ASSERT_EQ(pid.update(at(1.5, 1.0), 0.1), Status::Ok);
  EXPECT_NEAR(pid.integral(), 2.0 * 0.5 * 0.1, 1e-15);
  ASSERT_EQ(pid.update(at(1.0, 1.5), 0.2), Status::Ok);
  EXPECT_NEAR(pid.integral(), 0.1 - 2.0 * 0.5 * 0.2, 1e-15);
  EXPECT_NEAR(pid.output(), pid.integral(), 0.0);
  EXPECT_EQ(pid.terms().i, pid.integral());
}

// A joint that cannot move (blocked, or a huge load): the error never shrinks and the output
// saturates for the whole run.
Config saturating(AntiWindup anti_windup) {
  Config c = gains_only(0.5, 1.0, 0.0);
  c.output_min = -1.0;
  c.output_max = 1.0;
  c.anti_windup = anti_windup;
  c.tracking_gain_per_s = 2.0;
  return c;
}

TEST(Pid, WithoutAntiWindupTheIntegratorWindsUpUnderLongSaturation) {
  Pid pid(saturating(AntiWindup::None));
  for (int k = 0; k < 100000; ++k)
    ASSERT_EQ(pid.update(at(1.0, 0.0), 0.01), Status::Ok);
  EXPECT_NEAR(pid.integral(), 1.0 * 1.0 * 0.01 * 100000, 1e-6);
  EXPECT_EQ(pid.output(), 1.0);
  EXPECT_TRUE(pid.saturated());
}

TEST(Pid, ClampingFreezesTheIntegratorWhileSaturated) {
  Pid pid(saturating(AntiWindup::Clamping));
  double max_integral = 0.0;
  for (int k = 0; k < 100000; ++k) {
    ASSERT_EQ(pid.update(at(1.0, 0.0), 0.01), Status::Ok);
    max_integral = std::max(max_integral, pid.integral());
  }
  // It integrates until P + I reaches the limit and no further: I = 1 - P.
  EXPECT_NEAR(max_integral, 1.0 - 0.5, 1e-12);
  EXPECT_NEAR(pid.integral(), 1.0 - 0.5, 1e-12);
  EXPECT_EQ(pid.output(), 1.0);
}

TEST(Pid, ClampingLetsTheIntegratorDriveTheOutputUpToTheLimit) {
  // One increment (0.95) would overshoot the limit from P = 0.1; dropping it whole would hold the
  // output at 0.1, unsaturated, with integral action stopped for good.
  Config c = gains_only(0.1, 1.0, 0.0);
  c.output_min = -1.0;
  c.output_max = 1.0;
  c.anti_windup = AntiWindup::Clamping;
  Pid pid(c);
  for (int k = 0; k < 10; ++k)
    ASSERT_EQ(pid.update(at(1.0, 0.0), 0.95), Status::Ok);
  EXPECT_EQ(pid.output(), 1.0);
  EXPECT_NEAR(pid.integral(), 0.9, 1e-15);
}

TEST(Pid, BackCalculationBleedsTheIntegratorToItsTrackingEquilibrium) {
  Pid pid(saturating(AntiWindup::BackCalculation));
  for (int k = 0; k < 100000; ++k)
    ASSERT_EQ(pid.update(at(1.0, 0.0), 0.01), Status::Ok);
  // Equilibrium: Ki e dt + Kt (u - v) dt = 0, so v = u + Ki e / Kt; v is formed with this tick's
  // increment, v = P + I + Ki e dt, so the stored I = v - P - Ki e dt.
  EXPECT_NEAR(pid.integral(), 1.0 + 1.0 * 1.0 / 2.0 - 0.5 - 1.0 * 1.0 * 0.01, 1e-9);
  EXPECT_NEAR(pid.unsaturated_output(), 1.0 + 1.0 * 1.0 / 2.0, 1e-9);
  EXPECT_EQ(pid.output(), 1.0);
}

TEST(Pid, AntiWindupReleasesSaturationAsSoonAsTheErrorReverses) {
  for (const AntiWindup scheme : {AntiWindup::Clamping, AntiWindup::BackCalculation}) {
    Pid pid(saturating(scheme));
    for (int k = 0; k < 10000; ++k)
      ASSERT_EQ(pid.update(at(1.0, 0.0), 0.01), Status::Ok);
    ASSERT_EQ(pid.update(at(0.0, 0.5), 0.01), Status::Ok);
    EXPECT_LT(pid.output(), 1.0) << "scheme " << static_cast<int>(scheme);
  }
  Pid wound(saturating(AntiWindup::None));
  for (int k = 0; k < 10000; ++k)
    ASSERT_EQ(wound.update(at(1.0, 0.0), 0.01), Status::Ok);
  ASSERT_EQ(wound.update(at(0.0, 0.5), 0.01), Status::Ok);
  EXPECT_EQ(wound.output(), 1.0);  // ~100 of stored integral keeps it pinned
}

// Output limits [2, 10] do not straddle zero: the sign of error * output says nothing about
// whether integrating pushes further into saturation.
Config positive_limits() {
  Config c = gains_only(1.0, 1.0, 0.0);
  c.output_min = 2.0;
  c.output_max = 10.0;
  c.anti_windup = AntiWindup::Clamping;
  return c;
}

TEST(Pid, ClampingIntegratesOutOfTheLowerLimitEvenThoughErrorAndOutputArePositive) {
  Pid pid(positive_limits());
  ASSERT_EQ(pid.update(at(0.5, 0.0), 0.1), Status::Ok);  // v = 0.5 + 0.05 < 2: saturated low
  EXPECT_EQ(pid.output(), 2.0);
  EXPECT_NEAR(pid.integral(), 0.05, 1e-15);  // e > 0 pulls v up, towards the band: integrate
}

TEST(Pid, ClampingFreezesAtTheUpperLimitWithPositiveError) {
  Pid pid(positive_limits());
  ASSERT_EQ(pid.update(at(12.0, 0.0), 0.1), Status::Ok);  // v = 12 + 1.2 > 10
  EXPECT_EQ(pid.output(), 10.0);
  EXPECT_EQ(pid.integral(), 0.0);
}

TEST(Pid, ClampingFreezesAtTheLowerLimitWithNegativeError) {
  Pid pid(positive_limits());
  ASSERT_EQ(pid.update(at(0.0, 1.0), 0.1), Status::Ok);  // v = -1 - 0.1 < 2
  EXPECT_EQ(pid.output(), 2.0);
  EXPECT_EQ(pid.integral(), 0.0);
}

TEST(Pid, ClampingIntegratesOutOfTheUpperLimitWithNegativeError) {
  Pid pid(positive_limits());
  ASSERT_EQ(pid.initialize(20.0, at(0.0, 0.0)), Status::Ok);  // I = 20
  ASSERT_EQ(pid.update(at(0.0, 1.0), 0.1), Status::Ok);       // v = -1 + 20 - 0.1 > 10
  EXPECT_EQ(pid.output(), 10.0);
  EXPECT_NEAR(pid.integral(), 20.0 - 0.1, 1e-15);
}

TEST(Pid, IntegralLimitsBoundTheIntegralTerm) {
  Config c = gains_only(0.0, 1.0, 0.0);
  c.anti_windup = AntiWindup::None;
  c.integral_min = -0.25;
  c.integral_max = 0.5;
  Pid pid(c);
  for (int k = 0; k < 1000; ++k)
    ASSERT_EQ(pid.update(at(1.0, 0.0), 0.01), Status::Ok);
  EXPECT_EQ(pid.integral(), 0.5);
  EXPECT_EQ(pid.output(), 0.5);
  for (int k = 0; k < 1000; ++k)
    ASSERT_EQ(pid.update(at(-1.0, 0.0), 0.01), Status::Ok);
  EXPECT_EQ(pid.integral(), -0.25);
}

TEST(Pid, ChangingGainsOnlineDoesNotChangeTheOutputAtThatInstant) {
  const std::uint64_t seed = 41;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  fuzzypid::support::UniformReal<double> u(-1.0, 1.0);
  fuzzypid::support::UniformReal<double> g(0.0, 5.0);
  Config c = gains_only(1.0, 1.0, 0.1);
  c.derivative_source = DerivativeSource::Difference;
  Pid pid(c);
  for (int k = 0; k < 2000; ++k) {
    const double dt = 0.01;
    const Input in = at(u(rng), u(rng));
    ASSERT_EQ(pid.update(in, dt), Status::Ok);
    const double output = pid.output();
    const double integral = pid.integral();
    const Gains next{g(rng), g(rng), g(rng)};
    ASSERT_EQ(pid.set_gains(next), Status::Ok);
    ASSERT_EQ(pid.output(), output);
    ASSERT_EQ(pid.integral(), integral);
    ASSERT_EQ(pid.gains(), next);
    // The integral term continues from where it was: I_next = I + Ki_new e dt, never
    // Ki_new * (sum of e dt), which would jump by (Ki_new - Ki_old) * sum(e dt).
    const Input again = at(u(rng), u(rng));
    const double e = again.setpoint - again.measurement;
    ASSERT_EQ(pid.update(again, dt), Status::Ok);
    ASSERT_NEAR(pid.integral(), integral + next.ki * e * dt, 1e-12);
  }
}

TEST(Pid, KiOfZeroFreezesTheIntegralInsteadOfResettingIt) {
  Pid pid(gains_only(0.0, 1.0, 0.0));
  for (int k = 0; k < 10; ++k)
    ASSERT_EQ(pid.update(at(1.0, 0.0), 0.1), Status::Ok);
  const double integral = pid.integral();
  ASSERT_NEAR(integral, 1.0, 1e-12);
  ASSERT_EQ(pid.set_gains({0.0, 0.0, 0.0}), Status::Ok);
  for (int k = 0; k < 10; ++k)
    ASSERT_EQ(pid.update(at(1.0, 0.0), 0.1), Status::Ok);
  EXPECT_EQ(pid.integral(), integral);
  EXPECT_EQ(pid.output(), integral);
}

TEST(Pid, SetGainsRejectsNonFiniteGainsAndKeepsTheOldOnes) {
  Pid pid(gains_only(1.0, 2.0, 3.0));
  EXPECT_EQ(pid.set_gains({kNaN, 0.0, 0.0}), Status::NonFiniteInput);
  EXPECT_EQ(pid.set_gains({0.0, kInf, 0.0}), Status::NonFiniteInput);
  EXPECT_EQ(pid.gains(), (Gains{1.0, 2.0, 3.0}));
}

TEST(Pid, DerivativeOnMeasurementGivesNoKickOnASetpointStep) {
  for (const DerivativeOn on : {DerivativeOn::Error, DerivativeOn::Measurement}) {
    Config c = gains_only(0.0, 0.0, 2.0);
    c.derivative_source = DerivativeSource::Difference;
    c.derivative_on = on;
    Pid pid(c);
    for (int k = 0; k < 5; ++k)
      ASSERT_EQ(pid.update(at(0.0, 0.0), 0.01), Status::Ok);
    ASSERT_EQ(pid.update(at(1.0, 0.0), 0.01), Status::Ok);  // setpoint step, plant still
    if (on == DerivativeOn::Measurement) {
      EXPECT_EQ(pid.terms().d, 0.0);
      EXPECT_EQ(pid.output(), 0.0);
    } else {
      EXPECT_NEAR(pid.terms().d, 2.0 * 1.0 / 0.01, 1e-9);  // the kick Kd * step / dt
    }
  }
}

TEST(Pid, DerivativeOnMeasurementStillDampsPlantMotion) {
  Config c = gains_only(0.0, 0.0, 2.0);
  c.derivative_source = DerivativeSource::Difference;
  c.derivative_on = DerivativeOn::Measurement;
  Pid pid(c);
  ASSERT_EQ(pid.update(at(1.0, 0.0), 0.01), Status::Ok);
  EXPECT_EQ(pid.terms().d, 0.0);  // no previous sample: no derivative on the first tick
  ASSERT_EQ(pid.update(at(1.0, 0.03), 0.01), Status::Ok);
  EXPECT_NEAR(pid.terms().d, -2.0 * 0.03 / 0.01, 1e-12);
}

TEST(Pid, DerivativeFilterIsAFirstOrderLagWithTimeConstantTf) {
  // A unit step of the raw derivative (measured velocity -1 -> d_raw = 1) through
  // d_k = d_{k-1} + dt / (Tf + dt) (1 - d_{k-1}) gives d_k = 1 - (Tf / (Tf + dt))^k, the backward
  // Euler image of 1 - exp(-t / Tf). With h = dt / Tf, (1 + h)^-k <= exp(-k h + k h^2 / 2), so
  // |d_k - (1 - exp(-t/Tf))| <= exp(-s)(exp(s h / 2) - 1) with s = t / Tf, which is at most
  // about h / (2e) for small h.
  const double tf = 0.2;
  const double dt = 0.002;
  const double h = dt / tf;
  Config c = gains_only(0.0, 0.0, 1.0);
  c.derivative_filter_s = tf;
  Pid pid(c);
  ASSERT_EQ(pid.update(at(0.0, 0.0, 0.0), dt), Status::Ok);
  ASSERT_EQ(pid.derivative(), 0.0);
  const double bound = h / (2.0 * std::exp(1.0)) * (1.0 + h);
  for (int k = 1; k <= 1000; ++k) {
    ASSERT_EQ(pid.update(at(0.0, 0.0, -1.0), dt), Status::Ok);
    const double t = k * dt;
    ASSERT_NEAR(pid.derivative(), 1.0 - std::pow(tf / (tf + dt), k), 1e-12) << "tick " << k;
    ASSERT_NEAR(pid.derivative(), 1.0 - std::exp(-t / tf), bound) << "t = " << t;
    if (k == 100) {
      EXPECT_NEAR(pid.derivative(), 1.0 - std::exp(-1.0), bound);  // t = Tf
    }
  }
  EXPECT_NEAR(pid.terms().d, pid.derivative(), 0.0);
}

TEST(Pid, WithoutFilterTheDerivativeFollowsTheRawSignal) {
  Pid pid(gains_only(0.0, 0.0, 1.0));
  ASSERT_EQ(pid.update(at(0.0, 0.0, 0.0), 0.01), Status::Ok);
  ASSERT_EQ(pid.update(at(0.0, 0.0, -1.0), 0.01), Status::Ok);
  EXPECT_EQ(pid.derivative(), 1.0);
}

TEST(Pid, FeedForwardPassesThroughToTheOutput) {
  Pid pid(gains_only(2.0, 0.0, 0.0));
  Input in = at(1.0, 0.5);
  in.feed_forward = 3.0;
  ASSERT_EQ(pid.update(in, 0.01), Status::Ok);
  EXPECT_EQ(pid.output(), 2.0 * 0.5 + 3.0);
  EXPECT_EQ(pid.terms().p, 1.0);
}

TEST(Pid, FeedForwardIsCoveredByAntiWindup) {
  // P + I alone stay inside [-1, 1]; the feed-forward drives the output into the upper limit.
  for (const AntiWindup scheme :
       {AntiWindup::None, AntiWindup::Clamping, AntiWindup::BackCalculation}) {
    Config c = gains_only(0.1, 0.1, 0.0);
    c.output_min = -1.0;
    c.output_max = 1.0;
    c.anti_windup = scheme;
    c.tracking_gain_per_s = 1.0;
    Pid pid(c);
    Input in = at(1.0, 0.0);
    in.feed_forward = 5.0;
    for (int k = 0; k < 10000; ++k)
      ASSERT_EQ(pid.update(in, 0.01), Status::Ok);
    EXPECT_EQ(pid.output(), 1.0);
    switch (scheme) {
      case AntiWindup::None:
        EXPECT_NEAR(pid.integral(), 0.1 * 1.0 * 0.01 * 10000, 1e-9);
        break;
      case AntiWindup::Clamping:
        EXPECT_EQ(pid.integral(), 0.0);
        break;
      case AntiWindup::BackCalculation:
        // I = u + Ki e / Kt - P - ff - Ki e dt = 1 + 0.1 - 0.1 - 5 - 0.001.
        EXPECT_NEAR(pid.integral(), -4.001, 1e-9);
        break;
    }
  }
}

TEST(Pid, InitializeGivesABumplessStart) {
  Config c = gains_only(2.0, 0.5, 3.0);
  c.derivative_source = DerivativeSource::Difference;
  c.derivative_filter_s = 0.05;
  Pid pid(c);
  Input in = at(1.0, 0.8);
  in.feed_forward = 0.25;
  ASSERT_EQ(pid.initialize(1.7, in), Status::Ok);
  EXPECT_EQ(pid.output(), 1.7);
  EXPECT_TRUE(pid.has_previous());
  ASSERT_EQ(pid.update(in, 0.01), Status::Ok);
  // Same input: P + I + ff = 1.7 plus one integration step Ki e dt; no derivative spike.
  EXPECT_NEAR(pid.output(), 1.7 + 0.5 * 0.2 * 0.01, 1e-12);
  EXPECT_EQ(pid.terms().d, 0.0);
}

TEST(Pid, InitializeClampsTheIntegralIntoItsLimitsAndRejectsNonFiniteValues) {
  Config c = gains_only(1.0, 1.0, 0.0);
  c.integral_max = 0.5;
  Pid pid(c);
  ASSERT_EQ(pid.initialize(3.0, at(0.0, 0.0)), Status::Ok);
  EXPECT_EQ(pid.integral(), 0.5);
  EXPECT_EQ(pid.initialize(kNaN, at(0.0, 0.0)), Status::NonFiniteInput);
  EXPECT_EQ(pid.initialize(1.0, at(kInf, 0.0)), Status::NonFiniteInput);
  EXPECT_EQ(pid.integral(), 0.5);
}

TEST(Pid, ResetClearsEveryPieceOfState) {
  Config c = gains_only(1.0, 1.0, 1.0);
  c.derivative_filter_s = 0.1;
  Pid pid(c);
  for (int k = 0; k < 10; ++k)
    ASSERT_EQ(pid.update(at(1.0, 0.2, 0.3), 0.01), Status::Ok);
  pid.reset();
  EXPECT_EQ(pid.output(), 0.0);
  EXPECT_EQ(pid.integral(), 0.0);
  EXPECT_EQ(pid.derivative(), 0.0);
  EXPECT_EQ(pid.unsaturated_output(), 0.0);
  EXPECT_FALSE(pid.has_previous());
  EXPECT_FALSE(pid.saturated());
  EXPECT_EQ(pid.terms().p, 0.0);
}

// Every observable of a controller, to prove a fault changed nothing.
struct Snapshot {
  double output, unsaturated, integral, derivative, p, i, d, previous_error;
  bool saturated, has_previous;
  Gains gains;
  explicit Snapshot(const Pid& pid)
      : output(pid.output()),
        unsaturated(pid.unsaturated_output()),
        integral(pid.integral()),
        derivative(pid.derivative()),
        p(pid.terms().p),
        i(pid.terms().i),
        d(pid.terms().d),
        previous_error(pid.previous_error()),
        saturated(pid.saturated()),
        has_previous(pid.has_previous()),
        gains(pid.gains()) {}
};

void expect_unchanged(const Pid& pid, const Snapshot& s) {
  EXPECT_EQ(pid.output(), s.output);
  EXPECT_EQ(pid.unsaturated_output(), s.unsaturated);
  EXPECT_EQ(pid.integral(), s.integral);
  EXPECT_EQ(pid.derivative(), s.derivative);
  EXPECT_EQ(pid.terms().p, s.p);
  EXPECT_EQ(pid.terms().i, s.i);
  EXPECT_EQ(pid.terms().d, s.d);
  EXPECT_EQ(pid.previous_error(), s.previous_error);
  EXPECT_EQ(pid.saturated(), s.saturated);
  EXPECT_EQ(pid.has_previous(), s.has_previous);
  EXPECT_EQ(pid.gains(), s.gains);
}

Config busy_config(DerivativeSource source) {
  Config c = gains_only(2.0, 1.0, 0.5);
  c.derivative_source = source;
  c.derivative_filter_s = 0.05;
  c.output_min = -3.0;
  c.output_max = 3.0;
  return c;
}

TEST(Pid, NonFiniteInputsFaultAndLeaveEveryObservableUnchanged) {
  for (const auto source : {DerivativeSource::Rates, DerivativeSource::Difference}) {
    Pid pid(busy_config(source));
    Pid twin(busy_config(source));
    for (int k = 0; k < 20; ++k) {
      const Input in = at(1.0, 0.01 * k, 0.1);
      ASSERT_EQ(pid.update(in, 0.01), Status::Ok);
      ASSERT_EQ(twin.update(in, 0.01), Status::Ok);
    }
    for (const double bad : {kNaN, kInf, -kInf}) {
      for (int field = 0; field < 5; ++field) {
        Input in = at(1.0, 0.3, 0.1);
        in.setpoint_rate = 0.2;
        in.feed_forward = 0.1;
        double* fields[5] = {&in.setpoint, &in.measurement, &in.setpoint_rate, &in.measurement_rate,
                             &in.feed_forward};
        *fields[field] = bad;
        const bool rate_field = field == 2 || field == 3;
        if (rate_field && source == DerivativeSource::Difference) continue;  // rates unused
        const Snapshot before(pid);
        EXPECT_EQ(pid.update(in, 0.01), Status::NonFiniteInput) << "field " << field;
        expect_unchanged(pid, before);
      }
    }
    // The next good tick gives exactly what a controller that never saw the faults gives.
    const Input in = at(1.0, 0.25, 0.1);
    ASSERT_EQ(pid.update(in, 0.01), Status::Ok);
    ASSERT_EQ(twin.update(in, 0.01), Status::Ok);
    EXPECT_EQ(pid.output(), twin.output());
    EXPECT_EQ(pid.integral(), twin.integral());
    EXPECT_EQ(pid.derivative(), twin.derivative());
  }
}

TEST(Pid, UnusedRatesMayBeNonFiniteWithTheDifferenceSource) {
  Pid pid(busy_config(DerivativeSource::Difference));
  Input in = at(1.0, 0.5, kNaN);
  in.setpoint_rate = kInf;
  EXPECT_EQ(pid.update(in, 0.01), Status::Ok);
}

TEST(Pid, BadTimeStepsFaultAndLeaveEveryObservableUnchanged) {
  Pid pid(busy_config(DerivativeSource::Difference));
  for (int k = 0; k < 20; ++k)
    ASSERT_EQ(pid.update(at(1.0, 0.01 * k, 0.1), 0.01), Status::Ok);
  for (const double dt :
       {0.0, -0.0, -0.01, -kInf, kInf, kNaN, -std::numeric_limits<double>::denorm_min()}) {
    const Snapshot before(pid);
    EXPECT_EQ(pid.update(at(1.0, 0.5, 0.1), dt), Status::InvalidTimeStep) << "dt = " << dt;
    expect_unchanged(pid, before);
  }
  Pid fresh(busy_config(DerivativeSource::Rates));
  const Snapshot before(fresh);
  EXPECT_EQ(fresh.update(at(1.0, 0.0), 0.0), Status::InvalidTimeStep);
  expect_unchanged(fresh, before);
  EXPECT_FALSE(fresh.has_previous());
}

TEST(Pid, OverflowFromFiniteInputsIsReportedAndChangesNothing) {
  Pid pid(gains_only(1e300, 0.0, 0.0));
  ASSERT_EQ(pid.update(at(1.0, 0.0), 0.01), Status::Ok);
  const Snapshot before(pid);
  EXPECT_EQ(pid.update(at(1e300, -1e300), 0.01), Status::NumericOverflow);
  expect_unchanged(pid, before);

  Pid integral(gains_only(0.0, 1e308, 0.0));
  ASSERT_EQ(integral.update(at(1.0, 0.0), 1.0), Status::Ok);
  const Snapshot before_integral(integral);
  EXPECT_EQ(integral.update(at(1e10, 0.0), 1e10), Status::NumericOverflow);
  expect_unchanged(integral, before_integral);

  Config d = gains_only(0.0, 0.0, 1.0);
  d.derivative_source = DerivativeSource::Difference;
  Pid derivative(d);
  ASSERT_EQ(derivative.update(at(0.0, -1e308), 1.0), Status::Ok);
  const Snapshot before_derivative(derivative);
  EXPECT_EQ(derivative.update(at(0.0, 1e308), 1e-300), Status::NumericOverflow);
  expect_unchanged(derivative, before_derivative);
}

TEST(Pid, InvalidConfigIsRejected) {
  const Config good = gains_only(1.0, 0.0, 0.0);
  std::array<Config, 10> bad{};
  bad.fill(good);
  bad[0].gains.kp = kNaN;
  bad[1].gains.kd = kInf;
  bad[2].output_min = 2.0;
  bad[2].output_max = 1.0;
  bad[3].integral_min = 1.0;
  bad[3].integral_max = -1.0;
  bad[4].output_max = kNaN;
  bad[5].derivative_filter_s = -0.1;
  bad[6].derivative_filter_s = kInf;
  bad[7].tracking_gain_per_s = -1.0;
  bad[8].tracking_gain_per_s = kNaN;
  bad[9].integral_min = kNaN;
  for (std::size_t k = 0; k < bad.size(); ++k) {
    SCOPED_TRACE("bad config " + std::to_string(k));
    EXPECT_FALSE(bad[k].valid());
    Pid constructed(bad[k]);
    EXPECT_EQ(constructed.update(at(1.0, 0.0), 0.01), Status::InvalidConfig);
    EXPECT_EQ(constructed.output(), 0.0);
    Pid configured(good);
    EXPECT_EQ(configured.configure(bad[k]), Status::InvalidConfig);
    EXPECT_EQ(configured.config().gains, good.gains);
    EXPECT_EQ(configured.update(at(1.0, 0.0), 0.01), Status::Ok);
    EXPECT_EQ(configured.output(), 1.0);
  }
}

TEST(Pid, ConfigureAfterAnInvalidConstructionMakesItUsable) {
  Config bad = gains_only(kNaN, 0.0, 0.0);
  Pid pid(bad);
  ASSERT_EQ(pid.update(at(1.0, 0.0), 0.01), Status::InvalidConfig);
  ASSERT_EQ(pid.configure(gains_only(3.0, 0.0, 0.0)), Status::Ok);
  ASSERT_EQ(pid.update(at(1.0, 0.0), 0.01), Status::Ok);
  EXPECT_EQ(pid.output(), 3.0);
}

TEST(Pid, FloatInstantiationTracksDouble) {
  fuzzypid::pid::Config<float> cf;
  cf.gains = {2.0f, 0.5f, 0.1f};
  cf.output_min = -1.0f;
  cf.output_max = 1.0f;
  Config cd = gains_only(2.0, 0.5, 0.1);
  cd.output_min = -1.0;
  cd.output_max = 1.0;
  fuzzypid::pid::Pid<float> pf(cf);
  Pid pd(cd);
  for (int k = 0; k < 1000; ++k) {
    const float sp = 0.5f * std::sin(0.01f * static_cast<float>(k));
    fuzzypid::pid::Input<float> inf;
    inf.setpoint = sp;
    inf.measurement = 0.1f;
    ASSERT_EQ(pf.update(inf, 0.01f), Status::Ok);
    ASSERT_EQ(pd.update(at(sp, 0.1f), 0.01), Status::Ok);
    // |I| <= 3 over the run; 1000 float roundings of 2^-24 * 3 each stay below 2e-4.
    ASSERT_NEAR(pf.output(), pd.output(), 2e-4);
  }
}

// With the Rates source the derivative on measurement is -measurement_rate alone: a moving setpoint
// (setpoint_rate != 0) adds nothing, while on the error it adds Kd * setpoint_rate.
TEST(Pid, DerivativeOnMeasurementWithRatesIgnoresTheSetpointRate) {
  for (const DerivativeOn on : {DerivativeOn::Error, DerivativeOn::Measurement}) {
    Config c = gains_only(0.0, 0.0, 2.0);
    c.derivative_source = DerivativeSource::Rates;
    c.derivative_on = on;
    Pid pid(c);
    Input in = at(0.0, 0.0, 0.5);
    in.setpoint_rate = 3.0;
    ASSERT_EQ(pid.update(in, 0.01), Status::Ok);
    const double expected = on == DerivativeOn::Measurement ? 2.0 * -0.5 : 2.0 * (3.0 - 0.5);
    EXPECT_DOUBLE_EQ(pid.terms().d, expected);
    EXPECT_DOUBLE_EQ(pid.output(), expected);
  }
}

// --- Velocity observer (DerivativeSource::Observer) ---

Config observer_config(double bandwidth_hz, int delay_ticks) {
  Config c = gains_only(0.0, 0.0, 0.0);
  c.derivative_source = DerivativeSource::Observer;
  c.observer_bandwidth_hz = bandwidth_hz;
  c.observer_delay_ticks = delay_ticks;
  return c;
}

// The estimation error (y^ - y, w^ - w) of a joint that moves as the observer's model says obeys
// x_k = (I - L C) A x_{k-1}, whatever the command: checked against that product, tick by tick, for
// a command driven through the feed-forward, a wrong start rate and each modelled delay.
TEST(PidObserver, ItsErrorFollowsTheObserverMatrixForAJointThatMovesAsItsModel) {
  const double dt = 0.05, f = 1.5;
  const double p = 1.0 / (1.0 + 2.0 * 3.14159265358979323846 * f * dt);
  const double l1 = 1.0 - p * p, l2 = (1.0 - p) * (1.0 - p);
  for (int delay = 0; delay <= fuzzypid::pid::kMaxObserverDelayTicks; ++delay) {
    Pid pid(observer_config(f, delay));
    std::array<double, 8> commands{};  // newest first: what the joint receives `delay` ticks late
    DoubleIntegrator joint{1.0, 0.3, -0.2};
    const double start_rate_error = 0.7;
    double ex = 0.0, ev = start_rate_error;  // the error after the first tick
    for (int k = 0; k < 120; ++k) {
      Input in = at(0.0, joint.position, joint.velocity + (k == 0 ? start_rate_error : 0.0));
      in.feed_forward = std::sin(0.37 * k) * 4.0;
      ASSERT_EQ(pid.update(in, dt), Status::Ok);
      if (k > 0) {
        // Predicted error, then corrected: x = (I - L C) A x.
        const double px = ex + dt * ev, pv = ev;
        ex = (1.0 - l1) * px;
        ev = pv - l2 * px / dt;
      }
      EXPECT_NEAR(pid.derivative(), 0.0 - (joint.velocity + ev), 1e-9) << delay << " " << k;
      for (std::size_t j = commands.size() - 1; j > 0; --j)
        commands[j] = commands[j - 1];
      commands[0] = pid.output();
      joint.step(commands[static_cast<std::size_t>(delay)], dt);
    }
    EXPECT_LT(std::fabs(ev), 1e-6 * start_rate_error) << delay;
  }
}

// What the observer is for: an encoder of N counts per revolution read at a 50 ms tick. The
// differenced rate of a joint turning at a constant speed jumps by a count per tick, 2 pi / N /
// dt; the observer's estimate stays within a fifth of that (1 Hz), and the D term with it.
TEST(PidObserver, ItSmoothsTheRateOfACoarseEncoderThatDifferencingPassesOn) {
  const double dt = 0.05, count = 2.0 * 3.14159265358979323846 / 16384.0, speed = 0.0123;
  const auto quantised = [count](double x) { return std::round(x / count) * count; };
  Config difference = gains_only(0.0, 0.0, 1.0);
  difference.derivative_source = DerivativeSource::Difference;
  Config observer = observer_config(1.0, 1);
  observer.gains = {0.0, 0.0, 1.0};
  // The joint turns whatever the command: a model acceleration of u / 1e12 is none.
  observer.observer_output_per_unit = 1e12;
  Pid a(difference), b(observer);
  double worst_difference = 0.0, worst_observer = 0.0;
  for (int k = 0; k < 400; ++k) {
    const double y = speed * dt * k;
    Input in = at(0.0, quantised(y), k == 0 ? speed : 0.0);
    in.setpoint_rate = 0.0;
    ASSERT_EQ(a.update(in, dt), Status::Ok);
    ASSERT_EQ(b.update(in, dt), Status::Ok);
    if (k < 100) continue;  // settled
    worst_difference = std::max(worst_difference, std::fabs(-a.output() - speed));
    worst_observer = std::max(worst_observer, std::fabs(-b.output() - speed));
  }
  EXPECT_GT(worst_difference, 0.45 * count / dt);
  EXPECT_LT(worst_observer, 0.2 * count / dt);
}

// A fault leaves the observer as it was: the ticks after it are those of a run without it.
TEST(PidObserver, AFaultLeavesTheEstimateAndTheCommandHistoryUntouched) {
  Config c = observer_config(2.0, 1);
  c.gains = {3.0, 0.5, 0.8};
  Pid clean(c), faulted(c);
  for (int k = 0; k < 30; ++k) {
    const Input in = at(0.2, 0.01 * k, 0.1);
    if (k == 11) {
      EXPECT_EQ(faulted.update(at(0.2, kNaN), 0.05), Status::NonFiniteInput);
      EXPECT_EQ(faulted.update(in, -1.0), Status::InvalidTimeStep);
    }
    ASSERT_EQ(clean.update(in, 0.05), Status::Ok);
    ASSERT_EQ(faulted.update(in, 0.05), Status::Ok);
    EXPECT_EQ(clean.output(), faulted.output()) << k;
  }
}

// An observer switched on by configure() mid-run starts where the joint was last measured, at
// rest: a joint held still reads no rate on the first observed tick.
TEST(PidObserver, SwitchedOnMidRunItStartsAtTheLastMeasurementAtRest) {
  Config rates = gains_only(0.0, 0.0, 2.0);
  Pid pid(rates);
  for (int k = 0; k < 5; ++k)
    ASSERT_EQ(pid.update(at(0.0, 0.3, 0.0), 0.05), Status::Ok);
  Config observer = observer_config(1.0, 1);
  observer.gains = rates.gains;
  ASSERT_EQ(pid.configure(observer), Status::Ok);
  for (int k = 0; k < 5; ++k) {
    ASSERT_EQ(pid.update(at(0.0, 0.3, 0.0), 0.05), Status::Ok);
    EXPECT_EQ(pid.output(), 0.0) << k;
  }
}

// The observer reads the measured rate on its first tick only: a NaN rate faults that tick, and
// after it check() and update() agree that it is not read (the same output as a finite rate).
TEST(PidObserver, TheMeasuredRateIsReadOnTheFirstTickOnly) {
  Config c = observer_config(1.0, 1);
  c.gains = {2.0, 0.1, 0.5};
  Pid with_nan(c), with_rate(c);
  EXPECT_EQ(with_nan.check(at(0.1, 0.0, kNaN), 0.05), Status::NonFiniteInput);
  EXPECT_EQ(with_nan.update(at(0.1, 0.0, kNaN), 0.05), Status::NonFiniteInput);
  ASSERT_EQ(with_nan.update(at(0.1, 0.0, 0.2), 0.05), Status::Ok);
  ASSERT_EQ(with_rate.update(at(0.1, 0.0, 0.2), 0.05), Status::Ok);
  for (int k = 1; k < 20; ++k) {
    EXPECT_EQ(with_nan.check(at(0.1, 0.01 * k, kNaN), 0.05), Status::Ok);
    ASSERT_EQ(with_nan.update(at(0.1, 0.01 * k, kNaN), 0.05), Status::Ok);
    ASSERT_EQ(with_rate.update(at(0.1, 0.01 * k, 0.2), 0.05), Status::Ok);
    EXPECT_EQ(with_nan.output(), with_rate.output()) << k;
  }
  // The setpoint rate is read on every tick.
  Input bad = at(0.1, 0.3, 0.2);
  bad.setpoint_rate = kInf;
  EXPECT_EQ(with_nan.update(bad, 0.05), Status::NonFiniteInput);
}

// An observer needs a bandwidth, an output scale and a delay it models; anything else is refused.
TEST(PidObserver, AnObserverWithoutABandwidthOrBeyondThreeTicksIsRefused) {
  EXPECT_TRUE(observer_config(1.0, 0).valid());
  EXPECT_TRUE(observer_config(1.0, fuzzypid::pid::kMaxObserverDelayTicks).valid());
  EXPECT_FALSE(observer_config(0.0, 1).valid());
  EXPECT_FALSE(observer_config(kInf, 1).valid());
  EXPECT_FALSE(observer_config(kNaN, 1).valid());
  EXPECT_FALSE(observer_config(1.0, -1).valid());
  EXPECT_FALSE(observer_config(1.0, fuzzypid::pid::kMaxObserverDelayTicks + 1).valid());
  Config scale = observer_config(1.0, 1);
  scale.observer_output_per_unit = 0.0;
  EXPECT_FALSE(scale.valid());
  Pid pid;
  EXPECT_EQ(pid.configure(observer_config(0.0, 1)), Status::InvalidConfig);
  // Without the observer its settings are not read.
  Config rates = observer_config(0.0, 9);
  rates.derivative_source = DerivativeSource::Rates;
  EXPECT_TRUE(rates.valid());
}

// A PID that omits the observer's storage (the paper's controller) refuses the observer and keeps
// its configuration; with the rates or the differenced error it runs as one that carries it, bit
// for bit, over seeded random inputs, gains, limits and anti-windup schemes.
TEST(PidObserver, APidThatOmitsTheObserverRefusesItAndOtherwiseRunsAsOneThatCarriesIt) {
  using Lean = fuzzypid::pid::Pid<double, fuzzypid::pid::ObserverStorage::Omitted>;
  static_assert(sizeof(Lean) + 6 * sizeof(double) <= sizeof(Pid));
  Lean refused(observer_config(1.0, 1));
  EXPECT_EQ(refused.update(at(1.0, 0.0, 0.0), 0.05), Status::InvalidConfig);
  Lean lean(gains_only(2.0, 0.5, 0.1));
  EXPECT_EQ(lean.configure(observer_config(1.0, 1)), Status::InvalidConfig);
  EXPECT_EQ(lean.config().derivative_source, DerivativeSource::Rates);
  EXPECT_EQ(lean.update(at(1.0, 0.0, 0.0), 0.05), Status::Ok);

  std::mt19937_64 rng(20261206);
  const auto uniform = [&rng](double lo, double hi) {
    return fuzzypid::support::UniformReal<double>(lo, hi)(rng);
  };
  for (int trial = 0; trial < 200; ++trial) {
    Config c = gains_only(uniform(0.0, 10.0), uniform(0.0, 2.0), uniform(0.0, 1.0));
    c.derivative_source = trial % 2 == 0 ? DerivativeSource::Rates : DerivativeSource::Difference;
    c.derivative_on = trial % 3 == 0 ? DerivativeOn::Measurement : DerivativeOn::Error;
    c.anti_windup = static_cast<AntiWindup>(trial % 3);
    c.derivative_filter_s = uniform(0.0, 0.1);
    c.tracking_gain_per_s = uniform(0.0, 5.0);
    c.output_max = uniform(0.5, 5.0);
    c.output_min = -c.output_max;
    Lean a(c);
    Pid b(c);
    for (int k = 0; k < 50; ++k) {
      Input in = at(uniform(-1.0, 1.0), uniform(-1.0, 1.0), uniform(-2.0, 2.0));
      in.setpoint_rate = uniform(-2.0, 2.0);
      in.feed_forward = uniform(-0.5, 0.5);
      const Status sa = a.update(in, 0.05);
      ASSERT_EQ(sa, b.update(in, 0.05)) << trial << " " << k;
      ASSERT_EQ(a.output(), b.output()) << trial << " " << k;
      ASSERT_EQ(a.integral(), b.integral()) << trial << " " << k;
      ASSERT_EQ(a.derivative(), b.derivative()) << trial << " " << k;
    }
  }
}

}  // namespace
