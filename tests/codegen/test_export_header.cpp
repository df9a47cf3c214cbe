// `fuzzypid export-header`: the generated headers (built from the shipped controller files by
// tests/codegen/CMakeLists.txt, and from the test controllers of tests/sim/data) give
// controllers equal to the files' bit for bit on x86, and compile for float as well.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "engine_constructs_fuzzy.hpp"
#include "engine_disabled_fuzzy.hpp"
#include "engine_fuzzy.hpp"
#include "engine_lock_fuzzy.hpp"
#include "engine_tip_fuzzy.hpp"
#include "fuzzypid/codegen/export_header.hpp"
#include "fuzzypid/controller/joint_controllers.hpp"
#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid/sim/experiment.hpp"
#include "fuzzypid/sim/random.hpp"
#include "fuzzypid/supervisor/engine_supervisor.hpp"
#include "fuzzypid/supervisor/joint_controller.hpp"
#include "observer_pid.hpp"
#include "paper_fuzzy.hpp"
#include "per_joint_fuzzy.hpp"
#include "per_joint_pid.hpp"
#include "per_joint_scheduled.hpp"
#include "rule_table_fuzzy.hpp"
#include "tuned_fuzzy.hpp"
#include "tuned_fuzzy_rules.hpp"
#include "tuned_pid.hpp"
#include "tuned_scheduled.hpp"

namespace {

using namespace fuzzypid;
namespace cf = controller_file;
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
// Returns the number of ticks on which the supervisor fired some rule (both sides alike).
template <class Controller>
int expect_joints_equal_to_file(const char* file,
                                supervisor::JointController<double, kJ, Controller> from_header,
                                const char* folder) {
  int fired = 0;
  controller::ControllerSpec spec;
  fuzzypid::FileError err;
  EXPECT_TRUE(cf::load(std::string(FUZZYPID_SOURCE_DIR) + folder + file, spec, err))
      << err.to_string();
  std::string error;
  auto from_file =
      controller::JointControllers::create(spec, controller::Vector{3, 3, 3, 3, 3, 3}, error);
  EXPECT_TRUE(from_file) << error;
  if (!from_file) return 0;
  sim::Random rng(2024);
  for (int k = 0; k < 400; ++k) {
    controller::Input in;
    for (std::size_t i = 0; i < kJ; ++i) {
      in.desired_position_rad[i] = rng.uniform(-0.2, 0.2);
      in.desired_velocity_rad_s[i] = rng.uniform(-1.0, 1.0);
      in.measured_position_rad[i] = rng.uniform(-0.2, 0.2);
      in.measured_velocity_rad_s[i] = rng.uniform(-1.0, 1.0);
    }
    const auto a = from_file->step(in, spec.units.tick_s);
    const auto b = from_header.step(in, tuned_pid::kTickS);
    for (std::size_t i = 0; i < kJ; ++i) {
      EXPECT_TRUE(same_bits(a.output[i], b.output[i]))
          << file << " tick " << k << " joint " << i << ": " << a.output[i] << " vs "
          << b.output[i];
      EXPECT_EQ(a.joint_status[i], b.joint_status[i]);
      if (a.joint_status[i] != b.joint_status[i] || !same_bits(a.output[i], b.output[i]))
        return fired;
      fired += a.joint_status[i] == Status::Ok ? 1 : 0;
    }
  }
  return fired;
}

// The same with every joint a copy of the header's `prototype`.
template <class Controller>
int expect_equal_to_file(const char* file, const Controller& prototype,
                         const char* folder = "/controllers/") {
  return expect_joints_equal_to_file(
      file, supervisor::JointController<double, kJ, Controller>(prototype), folder);
}

TEST(ExportHeader, TheHeaderCarriesTheSimulatedPlantsNominalInertiaAndTorqueLimits) {
  // The shipped ER50 controllers are exported with the default robot: the bundled ER50-C20 on
  // the section 6 line, as sim_ab simulates it.
  std::string error;
  const auto ex = sim::Experiment::create(sim::RobotSetup{}, sim::ExperimentOptions{}, error);
  ASSERT_TRUE(ex) << error;
  const robot::JointVector limit = ex->torque_limit(sim::Condition{});
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(tuned_pid::kNominalInertiaKgm2[i], ex->nominal_inertia()[i]) << i;
    EXPECT_EQ(tuned_pid::kTorqueLimitNm[i], limit[i]) << i;
    // Acceleration gains: the output limit is the torque limit over J^, as the simulation's.
    EXPECT_EQ(tuned_pid::kOutputLimit[i],
              ex->output_limit(sim::Condition{}, controller::GainUnits::Acceleration)[i])
        << i;
  }
}

TEST(ExportHeader, GeneratedControllersEqualTheFilesBitForBit) {
  expect_equal_to_file("tuned_pid.toml", tuned_pid::make_controller<double>(3.0));
  expect_equal_to_file("tuned_scheduled.toml", tuned_scheduled::make_controller<double>(3.0));
  expect_equal_to_file("tuned_fuzzy.toml", tuned_fuzzy::make_controller<double>(3.0));
  expect_equal_to_file("tuned_fuzzy_rules.toml", tuned_fuzzy_rules::make_controller<double>(3.0));
  expect_equal_to_file("paper_fuzzy.toml", paper_fuzzy::make_controller<double>(3.0));
}

// The velocity observer (derivative = "observer") is part of the exported PID's configuration.
// A bandwidth scale per joint: the configuration functions take the joint, each joint's
// controller equals the file's joint bit for bit, and a joint past the sixth is refused.
template <class Controller, class Make>
void expect_per_joint_equal_to_file(const char* file, Make make) {
  std::array<Controller, kJ> joints;
  for (std::size_t i = 0; i < kJ; ++i)
    joints[i] = make(i);
  expect_joints_equal_to_file(file, supervisor::JointController<double, kJ, Controller>(joints),
                              "/tests/sim/data/");
  Controller beyond = make(kJ);
  EXPECT_EQ(beyond.update(typename Controller::Input{}, 0.05), Status::InvalidConfig) << file;
}

TEST(ExportHeader, AControllerWithABandwidthScalePerJointEqualsItsFileJointByJoint) {
  static_assert(per_joint_pid::kBandwidthScale[2] == 1.5, "the file's scale of joint 3");
  expect_per_joint_equal_to_file<per_joint_pid::Controller<double>>(
      "per_joint_pid.toml", [](std::size_t i) { return per_joint_pid::make_controller(i, 3.0); });
  expect_per_joint_equal_to_file<per_joint_scheduled::Controller<double>>(
      "per_joint_scheduled.toml",
      [](std::size_t i) { return per_joint_scheduled::make_controller(i, 3.0); });
  expect_per_joint_equal_to_file<per_joint_fuzzy::Controller<double>>(
      "per_joint_fuzzy.toml",
      [](std::size_t i) { return per_joint_fuzzy::make_controller(i, 3.0); });
}

TEST(ExportHeader, AControllerWithAVelocityObserverEqualsItsFileBitForBit) {
  constexpr auto config = observer_pid::pid_config<double>(3.0);
  static_assert(config.derivative_source == fuzzypid::pid::DerivativeSource::Observer);
  static_assert(config.observer_bandwidth_hz == 1.2 && config.observer_delay_ticks == 1);
  expect_equal_to_file("observer_pid.toml", observer_pid::make_controller<double>(3.0),
                       "/tests/sim/data/");
}

// Only a controller that runs the observer carries its state (pid::ObserverStorage).
TEST(ExportHeader, AControllerWithoutTheObserverOmitsItsStorage) {
  using fuzzypid::pid::ObserverStorage;
  static_assert(std::is_same_v<observer_pid::Controller<float>, fuzzypid::pid::Pid<float>>);
  static_assert(std::is_same_v<tuned_pid::Controller<float>,
                               fuzzypid::pid::Pid<float, ObserverStorage::Omitted>>);
  static_assert(sizeof(tuned_fuzzy::Controller<double>) + 6 * sizeof(double) <=
                sizeof(supervisor::FuzzyPid<double, tuned_fuzzy::Supervisor<double>>));
  // Asked for the observer anyway, the lean one refuses it.
  auto config = observer_pid::pid_config<double>(3.0);
  tuned_pid::Controller<double> lean;
  EXPECT_EQ(lean.configure(config), Status::InvalidConfig);
  config.derivative_source = fuzzypid::pid::DerivativeSource::Difference;
  EXPECT_EQ(lean.configure(config), Status::Ok);
}

TEST(ExportHeader, RuleFileControllersEqualTheFilesBitForBit) {
  // rulebases/paper.fll (zero-order Sugeno, triangles and shoulders) and Octave's Mamdani tipper
  // (trapezoids in; Gaussians and triangles out; centroid; hedges and `or`).
  EXPECT_GT(expect_equal_to_file("engine_fuzzy.toml", engine_fuzzy::make_controller<double>(3.0),
                                 "/tests/sim/data/"),
            400 * 6 / 2)
      << "most ticks fire rules";
  EXPECT_GT(
      expect_equal_to_file("engine_tip_fuzzy.toml", engine_tip_fuzzy::make_controller<double>(3.0),
                           "/tests/sim/data/"),
      400 * 6 / 2);
}

// lock_previous_supervisor.fll fires only for |Ke e| < 0.1 and keeps each output's last value
// elsewhere (lock-previous): once a rule has fired, every tick supervises with the last gains on
// both sides; a header that dropped lock-previous would fall back to K0 (NoRuleFired) there.
TEST(ExportHeader, AnExportedRuleBaseKeepsLockPrevious) {
  for (std::size_t o = 0; o < 3; ++o)
    EXPECT_TRUE(engine_lock_fuzzy::kRuleBase<double>.outputs[o].lock_previous) << "output " << o;
  EXPECT_GT(
      expect_equal_to_file("engine_lock_fuzzy.toml",
                           engine_lock_fuzzy::make_controller<double>(3.0), "/tests/sim/data/"),
      400 * 6 * 9 / 10)
      << "after its first firing each joint's supervisor answers on every tick";
}

// disabled_input_supervisor.fll: 'e is ZE or ec is ANY' with ec disabled fires only for
// |Ke e| < 0.1; a header that left ec enabled would fire everywhere.
TEST(ExportHeader, AnExportedRuleBaseKeepsADisabledInput) {
  EXPECT_TRUE(engine_disabled_fuzzy::kRuleBase<double>.inputs[0].enabled);
  EXPECT_FALSE(engine_disabled_fuzzy::kRuleBase<double>.inputs[1].enabled);
  const int fired =
      expect_equal_to_file("engine_disabled_fuzzy.toml",
                           engine_disabled_fuzzy::make_controller<double>(3.0), "/tests/sim/data/");
  EXPECT_GT(fired, 0);
  EXPECT_LT(fired, 400 * 6 / 2) << "most ticks lie in the gap";
}

template <class Scalar>
bool same_scalar_bits(Scalar a, Scalar b) {
  static_assert(sizeof(Scalar) <= sizeof(std::uint64_t));
  std::uint64_t x = 0, y = 0;
  std::memcpy(&x, &a, sizeof a);
  std::memcpy(&y, &b, sizeof b);
  return x == y;
}

// The (e, ec) a straight-line supervisor is checked at: seeded uniform values across and beyond
// the universe, every breakpoint of a term in `points` exactly (where a branch of a shape
// changes), and non-finite values.
template <class Scalar>
std::vector<std::array<Scalar, 2>> probe_inputs(const std::vector<double>& points,
                                                std::uint64_t seed) {
  std::vector<std::array<Scalar, 2>> in;
  in.reserve(20000 + points.size() * points.size() + 6);
  sim::Random rng(seed);
  for (int k = 0; k < 20000; ++k)
    in.push_back(
        {static_cast<Scalar>(rng.uniform(-1.5, 1.5)), static_cast<Scalar>(rng.uniform(-1.5, 1.5))});
  for (const double a : points)
    for (const double b : points)
      in.push_back({static_cast<Scalar>(a), static_cast<Scalar>(b)});
  const Scalar inf = std::numeric_limits<Scalar>::infinity();
  const Scalar nan = std::numeric_limits<Scalar>::quiet_NaN();
  for (const Scalar bad : {inf, -inf, nan}) {
    in.push_back({bad, Scalar(0)});
    in.push_back({Scalar(0), bad});
  }
  return in;
}

// The generated straight-line Supervisor against supervisor::EngineSupervisor on the same constexpr
// rule base (the interpreter), one workspace each carried across the whole sequence (so
// lock-previous is exercised): every status and every output bit must agree. Returns how many
// inferences fired some rule.
template <class Scalar, class Straight, class Model>
int expect_straight_line_equals_engine(const Straight& straight, const Model& model,
                                       const std::vector<double>& points, std::uint64_t seed) {
  const supervisor::EngineSupervisor<Scalar, typename Model::Capacity> engine(&model);
  EXPECT_TRUE(engine.valid());
  auto engine_ws = engine.make_workspace();
  auto straight_ws = straight.make_workspace();
  int fired = 0;
  for (const auto& x : probe_inputs<Scalar>(points, seed)) {
    std::array<Scalar, 3> a{}, b{};
    const Status sa = engine.infer(x[0], x[1], engine_ws, a);
    const Status sb = straight.infer(x[0], x[1], straight_ws, b);
    EXPECT_EQ(sa, sb) << "at e = " << x[0] << ", ec = " << x[1];
    for (std::size_t g = 0; g < 3; ++g)
      EXPECT_TRUE(same_scalar_bits(a[g], b[g]))
          << "gain " << g << " at e = " << x[0] << ", ec = " << x[1] << ": engine " << a[g]
          << ", straight-line " << b[g];
    if (sa != sb || !same_scalar_bits(a[0], b[0]) || !same_scalar_bits(a[1], b[1]) ||
        !same_scalar_bits(a[2], b[2]))
      return fired;
    fired += sa == Status::Ok ? 1 : 0;
  }
  return fired;
}

// A Sugeno rule base is exported as straight-line code (no interpreter, no workspace); the others
// keep the interpreted engine (a Mamdani output; a disabled input).
TEST(ExportHeader, ASugenoRuleBaseIsExportedAsStraightLineCode) {
  static_assert(std::is_empty_v<engine_fuzzy::Supervisor<float>::Workspace>);
  static_assert(std::is_empty_v<engine_constructs_fuzzy::Supervisor<double>::Workspace> == false,
                "lock-previous keeps the outputs' last values per joint");
  static_assert(std::is_same_v<engine_tip_fuzzy::Supervisor<float>::Workspace,
                               fuzzy::EngineWorkspace<float, engine_tip_fuzzy::RuleBaseCapacity>>);
  static_assert(
      std::is_same_v<engine_disabled_fuzzy::Supervisor<float>::Workspace,
                     fuzzy::EngineWorkspace<float, engine_disabled_fuzzy::RuleBaseCapacity>>);
  static_assert(supervisor::is_supervisor_v<engine_fuzzy::Supervisor<float>, float>);
  static_assert(supervisor::is_supervisor_v<engine_constructs_fuzzy::Supervisor<double>, double>);
}

// The paper's rules (rulebases/paper.fll): the straight-line code computes the engine's result bit
// for bit, in double and in float, across the universe, beyond it and at every breakpoint.
TEST(ExportHeader, TheStraightLinePaperSupervisorEqualsTheEngineBitForBit) {
  const std::vector<double> points = {-0.4, -0.3, -0.2, -0.1, 0.0, 0.1, 0.2, 0.3, 0.4};
  EXPECT_GT(expect_straight_line_equals_engine<double>(engine_fuzzy::kSupervisor<double>,
                                                       engine_fuzzy::kRuleBase<double>, points, 7),
            19000);
  EXPECT_GT(expect_straight_line_equals_engine<float>(engine_fuzzy::kSupervisor<float>,
                                                      engine_fuzzy::kRuleBase<float>, points, 8),
            19000);
}

// constructs_supervisor.fll: hedges in antecedents and conclusions, `any`, `or`, weights, a
// product conjunction, a Threshold block, linear terms, weighted sum, lock-range, a numeric
// default and lock-previous, bit for bit against the engine; lock_previous_supervisor.fll too.
// Inferences that fire nothing (the gaps) are part of the sequence.
TEST(ExportHeader, StraightLineCodeEqualsTheEngineOnEveryConstructItWrites) {
  const std::vector<double> points = {-1.5, -1.0, -0.6, -0.5, -0.3, 0.0, 0.3, 0.5, 0.8, 1.0, 1.5};
  for (const std::uint64_t seed : {11u, 12u}) {
    const int fired_double = expect_straight_line_equals_engine<double>(
        engine_constructs_fuzzy::kSupervisor<double>, engine_constructs_fuzzy::kRuleBase<double>,
        points, seed);
    EXPECT_GT(fired_double, 10000);
    const int fired_float = expect_straight_line_equals_engine<float>(
        engine_constructs_fuzzy::kSupervisor<float>, engine_constructs_fuzzy::kRuleBase<float>,
        points, seed);
    EXPECT_GT(fired_float, 10000);
  }
  EXPECT_GT(expect_straight_line_equals_engine<double>(engine_lock_fuzzy::kSupervisor<double>,
                                                       engine_lock_fuzzy::kRuleBase<double>,
                                                       {-0.1, 0.0, 0.1}, 13),
            1000);
}

TEST(ExportHeader, AnExportedRuleBaseIsConstexprDataSizedToTheFile) {
  static_assert(engine_fuzzy::kRuleBase<float>.num_rules == 49);
  static_assert(engine_fuzzy::RuleBaseCapacity::terms == 7 &&
                engine_fuzzy::RuleBaseCapacity::rules == 49);
  static_assert(engine_tip_fuzzy::kRuleBase<double>.num_outputs == 3);
  static_assert(engine_tip_fuzzy::kRuleBase<double>.num_rules == 6);
  EXPECT_FALSE(fuzzypid::fuzzy::validate(engine_fuzzy::kRuleBase<float>));
  EXPECT_FALSE(fuzzypid::fuzzy::validate(engine_tip_fuzzy::kRuleBase<float>));
  // The float controller runs: a positive error gives a positive command.
  auto joint = engine_tip_fuzzy::make_controller<float>(3.0f);
  pid::Input<float> in;
  in.setpoint = 0.1f;
  EXPECT_EQ(joint.update(in, 0.05f), Status::Ok);
  EXPECT_GT(joint.output(), 0.0f);
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

namespace {

// A tuned rule table as constexpr data: every ratio, center and R of the file, bit for bit (the
// random ticks above mostly saturate Ke e, so they reach few of the table's inner cells). The
// file is a table with cells other than 1 (the shipped one may be the schedule's start).
TEST(ExportHeader, TheFuzzyRulesTableIsTheFilesBitForBit) {
  controller::ControllerSpec spec;
  fuzzypid::FileError err;
  ASSERT_TRUE(cf::load(FUZZYPID_SOURCE_DIR "/tests/sim/data/rule_table_fuzzy.toml", spec, err))
      << err.to_string();
  const supervisor::RuleTable<double> file = controller::rule_table(spec);
  const auto& header = rule_table_fuzzy::kSupervisor<double>;
  bool some_cell_is_not_one = false;
  for (std::size_t g = 0; g < 3; ++g) {
    EXPECT_TRUE(same_bits(file.schedule_ratio[g], header.schedule_ratio[g]));
    for (std::size_t i = 0; i < 7; ++i) {
      EXPECT_TRUE(same_bits(file.e_centers[i], header.e_centers[i]));
      EXPECT_TRUE(same_bits(file.ec_centers[i], header.ec_centers[i]));
      for (std::size_t j = 0; j < 7; ++j) {
        EXPECT_TRUE(same_bits(file.table[g][i][j], header.table[g][i][j])) << g << i << j;
        some_cell_is_not_one = some_cell_is_not_one || header.table[g][i][j] != 1.0;
      }
    }
  }
  EXPECT_TRUE(some_cell_is_not_one);
}

}  // namespace

namespace {

// A rule-table cell beyond FLT_MAX would be written as a float literal that does not compile:
// check_float_range names the cell and its value first.
TEST(ExportHeader, ARuleTableCellBeyondTheFloatRangeIsRefusedNamingTheCell) {
  controller::ControllerSpec spec;
  fuzzypid::FileError err;
  ASSERT_TRUE(cf::load(FUZZYPID_SOURCE_DIR "/controllers/tuned_fuzzy_rules.toml", spec, err))
      << err.to_string();
  EXPECT_EQ(fuzzypid::codegen::check_float_range(spec), "");
  spec.supervisor.rule_table.ratio[2][6][5] = 1e300;
  const std::string bad = fuzzypid::codegen::check_float_range(spec);
  EXPECT_NE(bad.find("rule_table kd[6][5] (e PB, ec PM) is 1.0000000000000001e+300"),
            std::string::npos)
      << bad;
}

}  // namespace
