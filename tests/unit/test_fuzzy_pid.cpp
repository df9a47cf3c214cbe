// supervisor::FuzzyPid: the paper's fuzzy supervisor retuning a PID every tick (Eqs. 6-8).
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <limits>
#include <random>
#include <string>

#include "fuzzypid/paper.hpp"
#include "fuzzypid/supervisor/fuzzy_pid.hpp"
#include "fuzzypid_support/uniform_real.hpp"

namespace {

using fuzzypid::Status;
using fuzzypid::fuzzy::Conjunction;
using fuzzypid::fuzzy::LinguisticVariable;
using fuzzypid::fuzzy::Term;
using fuzzypid::paper::FuzzyPid;
using fuzzypid::pid::DerivativeSource;
using fuzzypid::supervisor::FuzzyPidConfig;
using fuzzypid::supervisor::GainUpdate;
using Gains = fuzzypid::pid::Gains<double>;
using Input = fuzzypid::pid::Input<double>;
namespace paper = fuzzypid::paper;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

Input at(double setpoint, double measurement, double setpoint_rate = 0.0,
         double measurement_rate = 0.0) {
  Input in;
  in.setpoint = setpoint;
  in.measurement = measurement;
  in.setpoint_rate = setpoint_rate;
  in.measurement_rate = measurement_rate;
  return in;
}

double clamp(double x, double lo, double hi) {
  return x < lo ? lo : (x > hi ? hi : x);
}

TEST(FuzzyPid, DefaultsToThePapersSystemGainsAndAbsoluteUpdate) {
  FuzzyPid<double> fpid = paper::make_fuzzy_pid<double>();
  EXPECT_EQ(fpid.config().gain_update, GainUpdate::Absolute);
  EXPECT_EQ(fpid.gains(), paper::kNominalGains<double>);
  EXPECT_EQ(fpid.config().pid.gains, (Gains{4.0, 0.001, 100.0}));
  EXPECT_EQ(fpid.config().error_scale, 1.0);
  EXPECT_EQ(fpid.nominal_gains(), fpid.gains());
}

TEST(FuzzyPid, AbsoluteModeSetsGainsToNominalPlusScaledDelta) {
  // K = K0 + S dK (Eq. 6), each gain clamped into [0, inf) by default.
  const std::uint64_t seed = 51;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  fuzzypid::support::UniformReal<double> u(-0.4, 0.4);
  for (const auto conjunction : {Conjunction::Minimum, Conjunction::Product}) {
    const auto system = paper::make_system<double>(conjunction);
    auto config = paper::paper_config<double>();
    config.output_scale = {10.0, 0.5, 20.0};
    FuzzyPid<double> fpid(&system, config);
    for (int k = 0; k < 2000; ++k) {
      const Input in = at(u(rng), u(rng), u(rng), u(rng));
      const double e = in.setpoint - in.measurement;
      const double ec = in.setpoint_rate - in.measurement_rate;
      ASSERT_EQ(fpid.update(in, 0.05), Status::Ok);
      const auto r = system.infer(e, ec);
      EXPECT_EQ(fpid.delta(), r.output);
      EXPECT_EQ(fpid.gains().kp, clamp(4.0 + 10.0 * r.output[0], 0.0, kInf));
      EXPECT_EQ(fpid.gains().ki, clamp(0.001 + 0.5 * r.output[1], 0.0, kInf));
      EXPECT_EQ(fpid.gains().kd, clamp(100.0 + 20.0 * r.output[2], 0.0, kInf));
      EXPECT_EQ(fpid.nominal_gains(), paper::kNominalGains<double>);  // K0 never drifts
    }
  }
}

TEST(FuzzyPid, AbsoluteModeIsMemoryless) {
  FuzzyPid<double> fpid = paper::make_fuzzy_pid<double>();
  for (int k = 0; k < 50; ++k)
    ASSERT_EQ(fpid.update(at(0.3, 0.0, 0.3, 0.0), 0.05), Status::Ok);
  const Gains after_many = fpid.gains();
  FuzzyPid<double> once = paper::make_fuzzy_pid<double>();
  ASSERT_EQ(once.update(at(0.3, 0.0, 0.3, 0.0), 0.05), Status::Ok);
  EXPECT_EQ(once.gains(), after_many);
  // (PL, PL): dKp = -0.03, dKd = 0.3 (Tables 2 and 4).
  EXPECT_NEAR(after_many.kp, 4.0 - 0.03, 1e-15);
  EXPECT_NEAR(after_many.kd, 100.0 + 0.3, 1e-12);
}

TEST(FuzzyPid, TheInnerPidRunsWithTheRetunedGains) {
  const auto system = paper::make_system<double>();
  FuzzyPid<double> fpid = paper::make_fuzzy_pid<double>();
  fuzzypid::pid::Pid<double> twin(fpid.config().pid);
  const std::uint64_t seed = 52;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  fuzzypid::support::UniformReal<double> u(-0.2, 0.2);
  for (int k = 0; k < 1000; ++k) {
    const Input in = at(u(rng), u(rng), u(rng), u(rng));
    const auto r =
        system.infer(in.setpoint - in.measurement, in.setpoint_rate - in.measurement_rate);
    ASSERT_EQ(
        twin.set_gains({clamp(4.0 + r.output[0], 0.0, kInf), clamp(0.001 + r.output[1], 0.0, kInf),
                        clamp(100.0 + r.output[2], 0.0, kInf)}),
        Status::Ok);
    ASSERT_EQ(twin.update(in, 0.05), Status::Ok);
    ASSERT_EQ(fpid.update(in, 0.05), Status::Ok);
    ASSERT_EQ(fpid.output(), twin.output());
    ASSERT_EQ(fpid.pid().integral(), twin.integral());
  }
}

TEST(FuzzyPid, IncrementalModeAccumulatesTheDeltas) {
  auto config = paper::paper_config<double>();
  config.gain_update = GainUpdate::Incremental;
  FuzzyPid<double> fpid(&paper::kSystem<double>, config);
  // (NL, NL): dKp = 0.03, dKi = -0.03, dKd = 0.1.
  const Input in = at(-0.3, 0.0, -0.3, 0.0);
  for (int k = 1; k <= 20; ++k) {
    ASSERT_EQ(fpid.update(in, 0.05), Status::Ok);
    EXPECT_NEAR(fpid.gains().kp, 4.0 + 0.03 * k, 1e-12);
    EXPECT_EQ(fpid.gains().ki, 0.0);  // 0.001 - 0.03 k is clamped at the default bound 0
    EXPECT_NEAR(fpid.gains().kd, 100.0 + 0.1 * k, 1e-12);
  }
}

TEST(FuzzyPid, IncrementalModeDriftsUntilTheGainBoundsStopIt) {
  auto config = paper::paper_config<double>();
  config.gain_update = GainUpdate::Incremental;
  config.gain_max = {4.5, 1.0, 101.0};
  FuzzyPid<double> fpid(&paper::kSystem<double>, config);
  for (int k = 0; k < 1000; ++k)
    ASSERT_EQ(fpid.update(at(-0.3, 0.0, -0.3, 0.0), 0.05), Status::Ok);
  EXPECT_EQ(fpid.gains().kp, 4.5);
  EXPECT_EQ(fpid.gains().kd, 101.0);
}

TEST(FuzzyPid, GainBoundsClampAndNoGainGoesNegativeByDefault) {
  auto config = paper::paper_config<double>();
  config.output_scale = {1000.0, 1000.0, 1000.0};
  FuzzyPid<double> fpid(&paper::kSystem<double>, config);
  // (NL, NL): dKp = 0.03, dKi = -0.03, dKd = 0.1, scaled by 1000.
  ASSERT_EQ(fpid.update(at(-0.3, 0.0, -0.3, 0.0), 0.05), Status::Ok);
  EXPECT_EQ(fpid.gains().ki, 0.0);
  EXPECT_NEAR(fpid.gains().kp, 34.0, 1e-12);
  // (NL, PS): dKd = -0.3 -> 100 - 300 < 0.
  ASSERT_EQ(fpid.update(at(-0.3, 0.0, 0.1, 0.0), 0.05), Status::Ok);
  EXPECT_EQ(fpid.gains().kd, 0.0);

  config.gain_min = {-kInf, -1.0, 50.0};
  config.gain_max = {10.0, kInf, kInf};
  FuzzyPid<double> signed_gains(&paper::kSystem<double>, config);
  ASSERT_EQ(signed_gains.update(at(-0.3, 0.0, -0.3, 0.0), 0.05), Status::Ok);
  EXPECT_EQ(signed_gains.gains().kp, 10.0);
  EXPECT_EQ(signed_gains.gains().ki, -1.0);  // asked for: Ki may go negative down to -1
  ASSERT_EQ(signed_gains.update(at(-0.3, 0.0, 0.1, 0.0), 0.05), Status::Ok);
  EXPECT_EQ(signed_gains.gains().kd, 50.0);
}

TEST(FuzzyPid, InputScalingMapsThePhysicalErrorOntoTheUniverse) {
  // Ke = 0.3 / e_max puts e = e_max on the PL peak; Kec likewise for ec.
  const double e_max = 0.05;  // rad
  const double ec_max = 0.5;  // rad/s
  const auto system = paper::make_system<double>();
  auto config = paper::paper_config<double>();
  config.error_scale = 0.3 / e_max;
  config.error_rate_scale = 0.3 / ec_max;
  FuzzyPid<double> fpid(&system, config);
  const std::uint64_t seed = 53;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  fuzzypid::support::UniformReal<double> ue(-1.5 * e_max, 1.5 * e_max);
  fuzzypid::support::UniformReal<double> uec(-1.5 * ec_max, 1.5 * ec_max);
  for (int k = 0; k < 2000; ++k) {
    const double e = ue(rng);
    const double ec = uec(rng);
    ASSERT_EQ(fpid.update(at(e, 0.0, ec, 0.0), 0.05), Status::Ok);
    EXPECT_EQ(fpid.delta(),
              system.infer(config.error_scale * e, config.error_rate_scale * ec).output);
  }
  ASSERT_EQ(fpid.update(at(e_max, 0.0, -ec_max, 0.0), 0.05), Status::Ok);
  EXPECT_NEAR(fpid.delta()[paper::kDeltaKp], paper::kDeltaKpPrinted[6][0], 1e-15);
  ASSERT_EQ(fpid.update(at(10.0 * e_max, 0.0, -10.0 * ec_max, 0.0), 0.05), Status::Ok);
  EXPECT_NEAR(fpid.delta()[paper::kDeltaKp], paper::kDeltaKpPrinted[6][0], 1e-15);  // saturates
}

TEST(FuzzyPid, DeltaIsReportedBeforeOutputScaling) {
  auto config = paper::paper_config<double>();
  config.output_scale = {2.0, 3.0, 4.0};
  FuzzyPid<double> fpid(&paper::kSystem<double>, config);
  ASSERT_EQ(fpid.update(at(0.3, 0.0, 0.3, 0.0), 0.05), Status::Ok);
  EXPECT_NEAR(fpid.delta()[0], -0.03, 1e-15);
  EXPECT_NEAR(fpid.gains().kp, 4.0 - 2.0 * 0.03, 1e-15);
  EXPECT_NEAR(fpid.gains().ki, 0.001 + 3.0 * 0.03, 1e-15);
  EXPECT_NEAR(fpid.gains().kd, 100.0 + 4.0 * 0.3, 1e-12);
}

TEST(FuzzyPid, DifferenceSourceComputesEcFromSuccessiveErrors) {
  const auto system = paper::make_system<double>();
  auto config = paper::paper_config<double>();
  config.pid.derivative_source = DerivativeSource::Difference;
  FuzzyPid<double> fpid(&system, config);
  const double dt = 0.5;
  // Rates are ignored with the difference source (even non-finite ones).
  ASSERT_EQ(fpid.update(at(0.1, 0.0, kNaN, 5.0), dt), Status::Ok);
  EXPECT_EQ(fpid.delta(), system.infer(0.1, 0.0).output);  // no previous error: ec = 0
  const double e1 = 0.1 - 0.0;
  const double e2 = 0.1 - 0.15;
  ASSERT_EQ(fpid.update(at(0.1, 0.15, 0.3, 5.0), dt), Status::Ok);
  EXPECT_EQ(fpid.delta(), system.infer(e2, (e2 - e1) / dt).output);
  ASSERT_EQ(fpid.update(at(0.0, 0.0), dt), Status::Ok);
  EXPECT_EQ(fpid.delta(), system.infer(0.0, (0.0 - e2) / dt).output);
}

// A supervisor whose inputs have a gap between their terms, so no rule fires near 0.5.
using GappySystem = fuzzypid::fuzzy::TskSystem<double, 2, 2, 3>;
GappySystem gappy_system() {
  GappySystem s;
  const std::array<Term<double>, 2> terms{Term<double>::left_shoulder(-0.3, 0.0),
                                          Term<double>::right_shoulder(1.0, 1.3)};
  s.e = LinguisticVariable<double, 2>::custom(-0.3, 1.3, terms);
  s.ec = s.e;
  for (auto& table : s.consequents)
    table = {{{{1.0, 1.0}}, {{1.0, 1.0}}}};
  return s;
}

TEST(FuzzyPid, NoRuleFiredKeepsTheNominalGainsAndStillRunsThePid) {
  auto config = paper::paper_config<double>();
  const GappySystem gappy = gappy_system();
  fuzzypid::supervisor::FuzzyPid<double, GappySystem> fpid(&gappy, config);
  fuzzypid::pid::Pid<double> twin(config.pid);
  ASSERT_EQ(fpid.update(at(-0.5, 0.0, -0.5, 0.0), 0.05), Status::Ok);  // fires: K0 + 1
  EXPECT_EQ(fpid.gains(), (Gains{5.0, 1.001, 101.0}));
  ASSERT_EQ(twin.set_gains(fpid.gains()), Status::Ok);
  ASSERT_EQ(twin.update(at(-0.5, 0.0, -0.5, 0.0), 0.05), Status::Ok);
  ASSERT_EQ(twin.set_gains(config.pid.gains), Status::Ok);
  const Input in = at(0.5, 0.0, 0.5, 0.0);
  EXPECT_EQ(fpid.update(in, 0.05), Status::NoRuleFired);
  EXPECT_EQ(fpid.gains(), config.pid.gains);
  EXPECT_EQ(fpid.delta(), (std::array<double, 3>{0.0, 0.0, 0.0}));
  ASSERT_EQ(twin.update(in, 0.05), Status::Ok);
  EXPECT_NE(fpid.output(), 0.0);
  EXPECT_NEAR(fpid.output(), twin.output(), 1e-12);
}

TEST(FuzzyPid, NoRuleFiredInIncrementalModeKeepsThePreviousGains) {
  auto config = paper::paper_config<double>();
  config.gain_update = GainUpdate::Incremental;
  const GappySystem gappy = gappy_system();
  fuzzypid::supervisor::FuzzyPid<double, GappySystem> fpid(&gappy, config);
  ASSERT_EQ(fpid.update(at(-0.5, 0.0, -0.5, 0.0), 0.05), Status::Ok);
  ASSERT_EQ(fpid.update(at(-0.5, 0.0, -0.5, 0.0), 0.05), Status::Ok);
  const Gains previous = fpid.gains();
  EXPECT_EQ(previous.kp, 6.0);
  EXPECT_EQ(fpid.update(at(0.5, 0.0, 0.5, 0.0), 0.05), Status::NoRuleFired);
  EXPECT_EQ(fpid.gains(), previous);
}

// The smallest supervisor of the concept (supervisor/supervisor.hpp): constant corrections, and a
// per-joint workspace that counts the inferences and records the last (e, ec).
struct ConstantSupervisor {
  struct Workspace {
    int calls = 0;
    double e = 0.0, ec = 0.0;
  };
  std::array<double, 3> delta{0.5, 0.25, 2.0};
  Workspace make_workspace() const { return {}; }
  Status infer(double e, double ec, Workspace& ws, std::array<double, 3>& out) const noexcept {
    ++ws.calls;
    ws.e = e;
    ws.ec = ec;
    out = delta;
    return Status::Ok;
  }
};
static_assert(fuzzypid::supervisor::is_supervisor_v<ConstantSupervisor, double>);
static_assert(fuzzypid::supervisor::is_supervisor_v<paper::System<float>, float>);
static_assert(!fuzzypid::supervisor::is_supervisor_v<paper::System<float>, double>);

TEST(FuzzyPid, AnySupervisorOfTheConceptSeesTheScaledErrorOncePerTick) {
  const ConstantSupervisor supervisor;
  auto config = paper::paper_config<double>();
  config.error_scale = 2.0;
  config.error_rate_scale = 3.0;
  fuzzypid::supervisor::FuzzyPid<double, ConstantSupervisor> fpid(&supervisor, config);
  ASSERT_EQ(fpid.update(at(0.5, 0.25, 0.1, 0.4), 0.05), Status::Ok);
  EXPECT_EQ(fpid.workspace().calls, 1);
  EXPECT_EQ(fpid.workspace().e, 2.0 * 0.25);
  EXPECT_EQ(fpid.workspace().ec, 3.0 * (0.1 - 0.4));
  EXPECT_EQ(fpid.gains(), (Gains{4.5, 0.251, 102.0}));
  EXPECT_EQ(fpid.supervisor(), &supervisor);
}

TEST(FuzzyPid, WithoutASupervisorItIsUnconfigured) {
  FuzzyPid<double> none;
  EXPECT_EQ(none.update(at(0.1, 0.0), 0.05), Status::InvalidConfig);
  FuzzyPid<double> null_supervisor(nullptr, paper::paper_config<double>());
  EXPECT_EQ(null_supervisor.update(at(0.1, 0.0), 0.05), Status::InvalidConfig);
  EXPECT_EQ(null_supervisor.configure(paper::paper_config<double>()), Status::InvalidConfig);
  EXPECT_EQ(null_supervisor.initialize(1.0, at(0.1, 0.0)), Status::InvalidConfig);
}

// Every observable of a fuzzy PID, to prove a fault changed nothing.
struct Snapshot {
  Gains gains, pid_gains;
  std::array<double, 3> delta;
  double output, integral, derivative, previous_error;
  bool has_previous;
  explicit Snapshot(const FuzzyPid<double>& f)
      : gains(f.gains()),
        pid_gains(f.pid().gains()),
        delta(f.delta()),
        output(f.output()),
        integral(f.pid().integral()),
        derivative(f.pid().derivative()),
        previous_error(f.pid().previous_error()),
        has_previous(f.pid().has_previous()) {}
  void expect_equal(const FuzzyPid<double>& f) const {
    EXPECT_EQ(f.gains(), gains);
    EXPECT_EQ(f.pid().gains(), pid_gains);
    EXPECT_EQ(f.delta(), delta);
    EXPECT_EQ(f.output(), output);
    EXPECT_EQ(f.pid().integral(), integral);
    EXPECT_EQ(f.pid().derivative(), derivative);
    EXPECT_EQ(f.pid().previous_error(), previous_error);
    EXPECT_EQ(f.pid().has_previous(), has_previous);
  }
};

TEST(FuzzyPid, FaultsLeaveGainsAndPidUntouched) {
  for (const auto mode : {GainUpdate::Absolute, GainUpdate::Incremental}) {
    auto config = paper::paper_config<double>();
    config.gain_update = mode;
    config.pid.derivative_filter_s = 0.1;
    FuzzyPid<double> fpid(&paper::kSystem<double>, config);
    for (int k = 0; k < 10; ++k)
      ASSERT_EQ(fpid.update(at(0.2, 0.01 * k, 0.1, 0.05), 0.05), Status::Ok);
    const Snapshot before(fpid);
    for (const double bad : {kNaN, kInf, -kInf}) {
      Input in = at(0.2, 0.1, 0.1, 0.05);
      in.setpoint = bad;
      EXPECT_EQ(fpid.update(in, 0.05), Status::NonFiniteInput);
      in = at(0.2, 0.1, 0.1, 0.05);
      in.measurement_rate = bad;
      EXPECT_EQ(fpid.update(in, 0.05), Status::NonFiniteInput);
      in = at(0.2, 0.1, 0.1, 0.05);
      in.feed_forward = bad;
      EXPECT_EQ(fpid.update(in, 0.05), Status::NonFiniteInput);
    }
    for (const double dt : {0.0, -0.05, kNaN, kInf})
      EXPECT_EQ(fpid.update(at(0.2, 0.1, 0.1, 0.05), dt), Status::InvalidTimeStep);
    before.expect_equal(fpid);
  }
}

TEST(FuzzyPid, OverflowInTheScaledInputsOrThePidChangesNothing) {
  auto config = paper::paper_config<double>();
  config.error_scale = 1e300;
  FuzzyPid<double> fpid(&paper::kSystem<double>, config);
  ASSERT_EQ(fpid.update(at(1e-301, 0.0), 0.05), Status::Ok);
  const Snapshot before(fpid);
  EXPECT_EQ(fpid.update(at(1e10, 0.0), 0.05), Status::NumericOverflow);  // Ke e = inf
  before.expect_equal(fpid);

  FuzzyPid<double> plain = paper::make_fuzzy_pid<double>();
  ASSERT_EQ(plain.update(at(0.1, 0.0), 0.05), Status::Ok);
  const Snapshot before_plain(plain);
  // Finite error, but Kp e overflows inside the PID: gains must be rolled back too.
  EXPECT_EQ(plain.update(at(1e308, 0.0), 0.05), Status::NumericOverflow);
  before_plain.expect_equal(plain);
}

TEST(FuzzyPid, InvalidConfigIsRejected) {
  const auto good = paper::paper_config<double>();
  std::array<FuzzyPidConfig<double>, 6> bad{};
  bad.fill(good);
  bad[0].error_scale = kNaN;
  bad[1].error_rate_scale = kInf;
  bad[2].output_scale[1] = kNaN;
  bad[3].gain_min.kp = 5.0;
  bad[3].gain_max.kp = 4.0;
  bad[4].gain_max.kd = kNaN;
  bad[5].pid.output_min = 1.0;
  bad[5].pid.output_max = -1.0;
  for (std::size_t k = 0; k < bad.size(); ++k) {
    SCOPED_TRACE("bad config " + std::to_string(k));
    EXPECT_FALSE(bad[k].valid());
    FuzzyPid<double> constructed(&paper::kSystem<double>, bad[k]);
    EXPECT_EQ(constructed.update(at(0.1, 0.0), 0.05), Status::InvalidConfig);
    FuzzyPid<double> configured = paper::make_fuzzy_pid<double>();
    EXPECT_EQ(configured.configure(bad[k]), Status::InvalidConfig);
    EXPECT_EQ(configured.update(at(0.1, 0.0), 0.05), Status::Ok);
  }
}

TEST(FuzzyPid, ResetAndInitializeRestoreTheNominalGains) {
  auto config = paper::paper_config<double>();
  config.gain_update = GainUpdate::Incremental;
  FuzzyPid<double> fpid(&paper::kSystem<double>, config);
  for (int k = 0; k < 5; ++k)
    ASSERT_EQ(fpid.update(at(0.3, 0.0, 0.3, 0.0), 0.05), Status::Ok);
  ASSERT_NE(fpid.gains(), config.pid.gains);
  fpid.reset();
  EXPECT_EQ(fpid.gains(), config.pid.gains);
  EXPECT_EQ(fpid.pid().gains(), config.pid.gains);
  EXPECT_EQ(fpid.output(), 0.0);
  EXPECT_FALSE(fpid.pid().has_previous());

  for (int k = 0; k < 5; ++k)
    ASSERT_EQ(fpid.update(at(0.3, 0.0, 0.3, 0.0), 0.05), Status::Ok);
  ASSERT_EQ(fpid.initialize(2.5, at(0.1, 0.0)), Status::Ok);
  EXPECT_EQ(fpid.gains(), config.pid.gains);
  EXPECT_EQ(fpid.output(), 2.5);
}

TEST(FuzzyPid, InitializeGivesABumplessStart) {
  // The next update retunes the gains from the same (e, ec) before the PID runs, so the output
  // must be the initialised one plus one integration step Ki' e dt, in either mode and after the
  // gains have drifted.
  for (const auto mode : {GainUpdate::Absolute, GainUpdate::Incremental}) {
    for (const auto source : {DerivativeSource::Rates, DerivativeSource::Difference}) {
      auto config = paper::paper_config<double>();
      config.gain_update = mode;
      config.pid.derivative_source = source;
      config.output_scale = {50.0, 1.0, 10.0};
      FuzzyPid<double> fpid(&paper::kSystem<double>, config);
      for (int k = 0; k < 20; ++k)
        ASSERT_EQ(fpid.update(at(0.3, 0.0, 0.3, 0.0), 0.05), Status::Ok);
      const Input in = at(0.25, 0.1);  // e = 0.15, no motion
      ASSERT_EQ(fpid.initialize(2.5, in), Status::Ok);
      EXPECT_EQ(fpid.output(), 2.5);
      ASSERT_EQ(fpid.update(in, 0.05), Status::Ok);
      const double e = 0.25 - 0.1;
      EXPECT_NEAR(fpid.output(), 2.5 + fpid.gains().ki * e * 0.05, 1e-12)
          << "mode " << to_string(mode) << ", source " << static_cast<int>(source);
    }
  }
}

TEST(FuzzyPid, FloatInstantiationTracksDouble) {
  FuzzyPid<float> ff = paper::make_fuzzy_pid<float>();
  FuzzyPid<double> fd = paper::make_fuzzy_pid<double>();
  for (int k = 0; k < 200; ++k) {
    const float e = 0.002f * static_cast<float>(k % 300) - 0.3f;
    fuzzypid::pid::Input<float> in;
    in.setpoint = e;
    in.setpoint_rate = -e;
    ASSERT_EQ(ff.update(in, 0.05f), Status::Ok);
    ASSERT_EQ(fd.update(at(e, 0.0, -e, 0.0), 0.05), Status::Ok);
    ASSERT_NEAR(ff.gains().kp, fd.gains().kp, 1e-5);
    ASSERT_NEAR(ff.gains().kd, fd.gains().kd, 1e-4);
    ASSERT_NEAR(ff.output(), fd.output(), 1e-3);
  }
}

}  // namespace
