// The tuner's vocabulary (fuzzypid/tune/parameters.hpp): every family's parameters land on their
// fields and come back, the exact conversions PID -> schedule -> rule table reproduce the
// controller's commands, the table's symmetry and held cells are what they say, and the
// regulariser costs exactly what it says.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "fuzzypid/controller/families.hpp"
#include "fuzzypid/controller/joint_controllers.hpp"
#include "fuzzypid/tune/parameters.hpp"
#include "fuzzypid_support/uniform_real.hpp"

namespace {

namespace controller = fuzzypid::controller;
namespace tune = fuzzypid::tune;

// The family a controller file calls `name` (the test fails for a name no family has).
controller::Family named_family(std::string_view name) {
  const std::optional<controller::Family> f = controller::parse_family(name);
  EXPECT_TRUE(f.has_value()) << name;
  return f.value_or(controller::Family{});
}

constexpr std::size_t kSets = controller::RuleTableSpec::kSets;

controller::ControllerSpec schedule() {
  controller::ControllerSpec s = controller::paper_pid();
  s.family = named_family("scheduled");
  s.gains = {40.0, 0.02, 300.0};
  s.supervisor.error_scale = 12.0;
  s.supervisor.error_rate_scale = 0.7;
  s.supervisor.output_scale = {0.3, 4.0, 1.6};
  return s;
}

controller::ControllerSpec converted(const controller::ControllerSpec& from,
                                     controller::Family to) {
  controller::ControllerSpec out;
  std::string error;
  EXPECT_TRUE(tune::convert(from, to, out, error)) << error;
  return out;
}

// Commands of two controllers on the same seeded random inputs, tick after tick (their integrals
// and filters evolve together as long as the commands agree); returns the largest difference
// relative to the command's size.
double largest_relative_difference(const controller::ControllerSpec& a,
                                   const controller::ControllerSpec& b) {
  controller::Vector limit;
  limit.fill(std::numeric_limits<double>::infinity());
  std::string error;
  auto ca = controller::JointControllers::create(a, limit, error);
  auto cb = controller::JointControllers::create(b, limit, error);
  EXPECT_TRUE(ca && cb) << error;
  if (!ca || !cb) return 1e9;
  std::mt19937_64 rng(7);
  fuzzypid::support::UniformReal<double> u(-0.2, 0.2);
  double worst = 0.0;
  for (int tick = 0; tick < 2000; ++tick) {
    controller::Input in;
    for (std::size_t j = 0; j < controller::kJoints; ++j) {
      in.desired_position_rad[j] = u(rng);
      in.measured_position_rad[j] = u(rng);
      in.desired_velocity_rad_s[j] = 5 * u(rng);
      in.measured_velocity_rad_s[j] = 5 * u(rng);
    }
    const controller::Command x = ca->step(in, 0.05);
    const controller::Command y = cb->step(in, 0.05);
    for (std::size_t j = 0; j < controller::kJoints; ++j) {
      const double scale = std::max(1.0, std::fabs(x.output[j]));
      worst = std::max(worst, std::fabs(x.output[j] - y.output[j]) / scale);
    }
  }
  return worst;
}

// The default boxes are per-tick gains at 0.05 s; at a 10 ms tick a loop as fast relative to its
// tick has five times the natural frequency: kp x 25, ki x 125, kd x 5, kec / 5.
TEST(BoxForTick, MovesEachGainsBoxByItsExponentOfTheTickRatio) {
  const double d = std::log10(5.0);
  for (const controller::Family family :
       {named_family("pid"), named_family("scheduled"), named_family("fuzzy")}) {
    const auto base = tune::default_box(family);
    const auto moved = tune::box_for_tick(base, family, 0.05, 0.01);
    ASSERT_EQ(moved.size(), base.size());
    for (std::size_t k = 0; k < base.size(); ++k) {
      const std::string& n = base[k].name;
      const bool fuzzy = family == named_family("fuzzy");
      const double exponent = n == "kp" || (fuzzy && n == "sp")   ? 2.0
                              : n == "ki" || (fuzzy && n == "si") ? 3.0
                              : n == "kd" || (fuzzy && n == "sd") ? 1.0
                              : n == "kec"                        ? -1.0
                                                                  : 0.0;
      EXPECT_NEAR(moved[k].log10_min, base[k].log10_min + exponent * d, 1e-12) << n;
      EXPECT_NEAR(moved[k].log10_max, base[k].log10_max + exponent * d, 1e-12) << n;
    }
    const auto same = tune::box_for_tick(base, family, 0.05, 0.05);
    for (std::size_t k = 0; k < base.size(); ++k)
      EXPECT_EQ(same[k].log10_min, base[k].log10_min);
  }
}

TEST(Convert, APidAsAScheduleGivesTheSameCommandsBitForBit) {
  controller::ControllerSpec pid = controller::paper_pid();
  pid.gains = {40.0, 0.02, 300.0};
  EXPECT_EQ(largest_relative_difference(pid, converted(pid, named_family("scheduled"))), 0.0);
}

TEST(Convert, AScheduleAsARuleTableGivesTheSameCommandsToRounding) {
  const controller::ControllerSpec s = schedule();
  const controller::ControllerSpec t = converted(s, named_family("fuzzy-rules"));
  EXPECT_EQ(t.family, named_family("fuzzy-rules"));
  EXPECT_EQ(t.supervisor.output_scale, s.supervisor.output_scale);
  // K0 + K0 ((R - 1) w) against K0 + (K0 (R - 1)) w: a few ulp of the gains.
  EXPECT_LT(largest_relative_difference(s, t), 1e-13);
  // and not by accident: one changed cell is seen
  controller::ControllerSpec bumped = t;
  bumped.supervisor.rule_table.ratio[0][kSets / 2][kSets / 2] = 1.01;
  EXPECT_GT(largest_relative_difference(s, bumped), 1e-6);
}

TEST(Convert, APidAsARuleTableIsThePid) {
  controller::ControllerSpec pid = controller::paper_pid();
  pid.gains = {40.0, 0.02, 300.0};
  EXPECT_LT(largest_relative_difference(pid, converted(pid, named_family("fuzzy-rules"))), 1e-15);
}

TEST(Convert, ConversionsWithoutAnExactFormAreRefused) {
  controller::ControllerSpec out;
  std::string error;
  EXPECT_FALSE(tune::convert(controller::paper_fuzzy(), named_family("scheduled"), out, error));
  EXPECT_NE(error.find("no exact"), std::string::npos);
  EXPECT_FALSE(tune::convert(schedule(), named_family("pid"), out, error));
  EXPECT_FALSE(tune::convert(controller::paper_fuzzy(), named_family("fuzzy-rules"), out, error));
  EXPECT_FALSE(tune::convert(converted(schedule(), named_family("fuzzy-rules")),
                             named_family("scheduled"), out, error));
}

tune::VisitMap all_visited() {
  tune::VisitMap v{};
  for (auto& row : v)
    for (double& x : row)
      x = 1.0 / (kSets * kSets);
  return v;
}

tune::ParameterSpace space(tune::Symmetry symmetry, bool partition,
                           const tune::VisitMap& visits = all_visited()) {
  tune::TableOptions o;
  o.symmetry = symmetry;
  o.partition = partition;
  std::string error;
  auto p = tune::ParameterSpace::create(named_family("fuzzy-rules"),
                                        converted(schedule(), named_family("fuzzy-rules")), o,
                                        &visits, error);
  EXPECT_TRUE(p) << error;
  return *p;
}

std::vector<double> random_point(const tune::ParameterSpace& p, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::vector<double> x;
  for (const auto& b : p.box())
    x.push_back(fuzzypid::support::UniformReal<double>(b.log10_min, b.log10_max)(rng));
  return x;
}

TEST(ParameterSpace, EachFamilySearchesItsNamedParameters) {
  EXPECT_EQ(tune::default_box(named_family("pid")).size(), 3u);
  EXPECT_EQ(tune::default_box(named_family("scheduled")).size(), 8u);
  EXPECT_EQ(tune::default_box(named_family("fuzzy"))[5].name, "sp");
  EXPECT_EQ(tune::default_box(named_family("scheduled"))[5].name, "rp");
  EXPECT_EQ(space(tune::Symmetry::Even, false).box().size(), 8u + 3 * 16);
  EXPECT_EQ(space(tune::Symmetry::Odd, false).box().size(), 8u + 3 * 24);
  EXPECT_EQ(space(tune::Symmetry::None, true).box().size(), 8u + 4 + 3 * 49);
  EXPECT_EQ(space(tune::Symmetry::None, false).box()[8].name, "kp[0,0]");
}

TEST(ParameterSpace, APointBecomesAControllerAndComesBack) {
  for (auto sym : {tune::Symmetry::Even, tune::Symmetry::Odd, tune::Symmetry::None})
    for (bool partition : {false, true}) {
      const tune::ParameterSpace p = space(sym, partition);
      for (unsigned seed = 1; seed <= 20; ++seed) {
        const std::vector<double> x = random_point(p, seed);
        const controller::ControllerSpec s = p.to_spec(x);
        EXPECT_EQ(controller::validate(s), "");
        const std::vector<double> back = p.from_spec(s);
        ASSERT_EQ(back.size(), x.size());
        for (std::size_t k = 0; k < x.size(); ++k)
          EXPECT_NEAR(back[k], x[k], 1e-12) << p.box()[k].name;
      }
    }
}

TEST(ParameterSpace, TheTableHasTheSymmetryItWasAskedFor) {
  const controller::ControllerSpec even =
      space(tune::Symmetry::Even, false)
          .to_spec(random_point(space(tune::Symmetry::Even, false), 3));
  const controller::ControllerSpec odd =
      space(tune::Symmetry::Odd, false).to_spec(random_point(space(tune::Symmetry::Odd, false), 3));
  const controller::ControllerSpec none =
      space(tune::Symmetry::None, false)
          .to_spec(random_point(space(tune::Symmetry::None, false), 3));
  bool none_is_even = true;
  for (std::size_t g = 0; g < 3; ++g)
    for (std::size_t i = 0; i < kSets; ++i)
      for (std::size_t j = 0; j < kSets; ++j) {
        const auto& e = even.supervisor.rule_table.ratio[g];
        EXPECT_EQ(e[i][j], e[kSets - 1 - i][j]);
        EXPECT_EQ(e[i][j], e[i][kSets - 1 - j]);
        const auto& o = odd.supervisor.rule_table.ratio[g];
        EXPECT_NEAR(std::log10(o[i][j]), -std::log10(o[kSets - 1 - i][kSets - 1 - j]), 1e-12);
        const auto& n = none.supervisor.rule_table.ratio[g];
        if (n[i][j] != n[kSets - 1 - i][j]) none_is_even = false;
      }
  EXPECT_EQ(odd.supervisor.rule_table.ratio[1][kSets / 2][kSets / 2], 1.0);
  EXPECT_FALSE(none_is_even);
}

TEST(ParameterSpace, TheSearchedPartitionStaysOrderedAndSymmetric) {
  const tune::ParameterSpace p = space(tune::Symmetry::Even, true);
  for (unsigned seed = 1; seed <= 50; ++seed) {
    const controller::ControllerSpec s = p.to_spec(random_point(p, seed));
    EXPECT_EQ(controller::validate(s.supervisor.rule_table), "");
    EXPECT_EQ(s.supervisor.rule_table.error_centers.back(), 1.0);  // the outer center is kept
  }
}

TEST(ParameterSpace, CellsTrainingNeverVisitsKeepTheStartsValues) {
  tune::VisitMap v{};
  for (std::size_t i = 2; i <= 4; ++i)
    for (std::size_t j = 2; j <= 4; ++j)
      v[i][j] = 1.0 / 9.0;  // only the nine center nodes fire
  controller::ControllerSpec start = converted(schedule(), named_family("fuzzy-rules"));
  start.supervisor.rule_table.ratio[2][0][0] = 3.0;  // an unvisited corner the start sets
  tune::TableOptions o;
  o.symmetry = tune::Symmetry::None;
  std::string error;
  auto p = tune::ParameterSpace::create(named_family("fuzzy-rules"), start, o, &v, error);
  ASSERT_TRUE(p) << error;
  EXPECT_EQ(p->box().size(), 8u + 3 * 9);
  EXPECT_EQ(p->held_cells(), 3u * 40);
  const controller::ControllerSpec s = p->to_spec(random_point(*p, 9));
  EXPECT_EQ(s.supervisor.rule_table.ratio[2][0][0], 3.0);
  EXPECT_EQ(s.supervisor.rule_table.ratio[0][6][1], 1.0);
  EXPECT_NE(s.supervisor.rule_table.ratio[0][3][3], 1.0);
  // free: every cell searched
  o.unvisited = tune::Unvisited::Free;
  auto q = tune::ParameterSpace::create(named_family("fuzzy-rules"), start, o, &v, error);
  ASSERT_TRUE(q) << error;
  EXPECT_EQ(q->box().size(), 8u + 3 * 49);
  EXPECT_EQ(q->held_cells(), 0u);
}

TEST(ParameterSpace, SmoothnessCostsTheSquaredStepsBetweenNeighbours) {
  tune::TableOptions o;
  o.symmetry = tune::Symmetry::None;
  o.unvisited = tune::Unvisited::Free;
  o.smoothness = 2.0;
  std::string error;
  const controller::ControllerSpec start = converted(schedule(), named_family("fuzzy-rules"));
  auto p = tune::ParameterSpace::create(named_family("fuzzy-rules"), start, o, nullptr, error);
  ASSERT_TRUE(p) << error;
  EXPECT_EQ(p->penalty(start), 0.0);  // a flat table
  controller::ControllerSpec bumped = start;
  bumped.supervisor.rule_table.ratio[1][3][2] = 100.0;  // log10 step of 2 to four neighbours
  EXPECT_NEAR(p->penalty(bumped), 2.0 * 4 * 4.0, 1e-12);
  bumped.supervisor.rule_table.ratio[1][0][0] = 0.1;  // a corner: two neighbours, step 1
  EXPECT_NEAR(p->penalty(bumped), 2.0 * (16.0 + 2.0), 1e-12);
}

TEST(ParameterSpace, MonotoneCostsOnlyStepsAgainstTheSchedulesDirection) {
  tune::TableOptions o;
  o.symmetry = tune::Symmetry::None;
  o.unvisited = tune::Unvisited::Free;
  o.monotone = 1.0;
  std::string error;
  const controller::ControllerSpec start = converted(schedule(), named_family("fuzzy-rules"));
  auto p = tune::ParameterSpace::create(named_family("fuzzy-rules"), start, o, nullptr, error);
  ASSERT_TRUE(p) << error;
  // The schedule itself moves each gain monotonically outwards: no cost.
  EXPECT_EQ(p->penalty(start), 0.0);
  // Rp = 0.3 < 1: Kp falls outwards. Lowering the outermost corner keeps it falling: no cost.
  controller::ControllerSpec lower = start;
  lower.supervisor.rule_table.ratio[0][6][6] = 0.5;
  EXPECT_EQ(p->penalty(lower), 0.0);
  // Lowering an edge cell makes Kp rise again towards its outer neighbour along the edge: the
  // squared log10 step, once: (log10(0.3) - log10(0.3 x 0.5))^2 ...
  controller::ControllerSpec dip = start;
  dip.supervisor.rule_table.ratio[0][6][3] = 0.5;
  EXPECT_NEAR(p->penalty(dip), 2 * std::pow(std::log10(2.0), 2), 1e-12);  // ... on both sides
  // Raising Kp further out costs.
  controller::ControllerSpec raise = start;
  raise.supervisor.rule_table.ratio[0][6][6] = 10.0;
  EXPECT_GT(p->penalty(raise), 0.1);
}

// R = 1 (a gain the schedule leaves at K0) counts as rising: never down outwards.
TEST(ParameterSpace, MonotoneTakesARatioOfOneAsNeverDown) {
  tune::TableOptions o;
  o.symmetry = tune::Symmetry::None;
  o.unvisited = tune::Unvisited::Free;
  o.monotone = 1.0;
  controller::ControllerSpec flat = schedule();
  flat.supervisor.output_scale = {1.0, 1.0, 1.0};
  std::string error;
  const controller::ControllerSpec start = converted(flat, named_family("fuzzy-rules"));
  auto p = tune::ParameterSpace::create(named_family("fuzzy-rules"), start, o, nullptr, error);
  ASSERT_TRUE(p) << error;
  EXPECT_EQ(p->penalty(start), 0.0);
  // Raising Ki's outermost corner keeps it rising outwards: no cost.
  controller::ControllerSpec raise = start;
  raise.supervisor.rule_table.ratio[1][6][6] = 10.0;
  EXPECT_EQ(p->penalty(raise), 0.0);
  // Lowering it is a step down from both inner neighbours: (log10 2)^2 twice.
  controller::ControllerSpec lower = start;
  lower.supervisor.rule_table.ratio[1][6][6] = 0.5;
  EXPECT_NEAR(p->penalty(lower), 2 * std::pow(std::log10(2.0), 2), 1e-12);
}

}  // namespace

// --search-filter: every family gains "tf", the last parameter, log10 of the derivative filter's
// time constant (s), which to_spec writes into the PID options and from_spec reads back; the
// family's own parameters keep their places (the partition and cells are read by index).
TEST(SearchFilter, TfIsTheLastParameterOfEveryFamilyAndRoundTrips) {
  for (const controller::Family family : {named_family("pid"), named_family("scheduled"),
                                          named_family("fuzzy"), named_family("fuzzy-rules")}) {
    const controller::ControllerSpec start =
        family == named_family("fuzzy-rules") ? converted(schedule(), named_family("fuzzy-rules"))
                                              : controller::paper_pid();
    tune::TableOptions o;
    o.unvisited = tune::Unvisited::Free;
    std::string error;
    const auto plain = tune::ParameterSpace::create(family, start, o, nullptr, error);
    const auto filtered = tune::ParameterSpace::create(family, start, o, nullptr, error, true);
    ASSERT_TRUE(plain && filtered) << error;
    ASSERT_EQ(filtered->box().size(), plain->box().size() + 1);
    for (std::size_t k = 0; k < plain->box().size(); ++k)
      EXPECT_EQ(filtered->box()[k].name, plain->box()[k].name);
    EXPECT_EQ(filtered->box().back().name, "tf");
    EXPECT_EQ(filtered->box().back().log10_min, -3.0);
    EXPECT_EQ(filtered->box().back().log10_max, 0.0);

    std::vector<double> x = plain->from_spec(start);
    x.push_back(std::log10(0.08));
    const controller::ControllerSpec s = filtered->to_spec(x);
    EXPECT_NEAR(s.pid.derivative_filter_s, 0.08, 1e-15);
    EXPECT_NEAR(s.gains.kd, plain->to_spec(plain->from_spec(start)).gains.kd,
                1e-9 * start.gains.kd);
    const std::vector<double> back = filtered->from_spec(s);
    ASSERT_EQ(back.size(), x.size());
    EXPECT_NEAR(back.back(), std::log10(0.08), 1e-12);
    // Without the option the start's filter is kept.
    EXPECT_EQ(plain->to_spec(plain->from_spec(start)).pid.derivative_filter_s,
              start.pid.derivative_filter_s);
    // A start without a filter enters the space at 1 ms, the box's lower end.
    EXPECT_EQ(filtered->from_spec(start).back(), -3.0);
  }
}

// tf is a time: at a 10 ms tick its box moves down by log10(5), like 1 / omega.
TEST(SearchFilter, TfsBoxMovesWithTheTick) {
  const std::vector<tune::SearchBox> box = {{"tf", -3.0, 0.0}};
  const auto moved = tune::box_for_tick(box, named_family("pid"), 0.05, 0.01);
  EXPECT_NEAR(moved[0].log10_min, -3.0 - std::log10(5.0), 1e-12);
  EXPECT_NEAR(moved[0].log10_max, -std::log10(5.0), 1e-12);
}

// A start whose derivative is the velocity observer adds "observer_hz" after "tf": log10 of the
// observer's bandwidth (Hz), which to_spec writes and from_spec reads back, tf keeping its value;
// without --search-filter, or without the observer, nothing is added.
TEST(SearchFilter, AnObserversBandwidthIsSearchedAfterTfAndRoundTrips) {
  controller::ControllerSpec start = controller::paper_pid();
  start.pid.derivative = fuzzypid::pid::DerivativeSource::Observer;
  start.pid.observer_bandwidth_hz = 1.0;
  for (const controller::Family family :
       {named_family("pid"), named_family("scheduled"), named_family("fuzzy")}) {
    tune::TableOptions o;
    std::string error;
    const auto plain =
        tune::ParameterSpace::create(family, controller::paper_pid(), o, nullptr, error, true);
    const auto observed = tune::ParameterSpace::create(family, start, o, nullptr, error, true);
    const auto kept = tune::ParameterSpace::create(family, start, o, nullptr, error, false);
    ASSERT_TRUE(plain && observed && kept) << error;
    ASSERT_EQ(observed->box().size(), plain->box().size() + 1);
    EXPECT_EQ(kept->box().size(), plain->box().size() - 1);
    EXPECT_EQ(observed->box()[observed->box().size() - 2].name, "tf");
    EXPECT_EQ(observed->box().back().name, "observer_hz");
    EXPECT_EQ(observed->box().back().log10_min, -1.0);
    EXPECT_EQ(observed->box().back().log10_max, 1.0);

    std::vector<double> x = observed->from_spec(start);
    EXPECT_EQ(x.back(), 0.0);  // 1 Hz
    x[x.size() - 2] = std::log10(0.02);
    x.back() = std::log10(3.5);
    const controller::ControllerSpec s = observed->to_spec(x);
    EXPECT_NEAR(s.pid.derivative_filter_s, 0.02, 1e-15);
    EXPECT_NEAR(s.pid.observer_bandwidth_hz, 3.5, 1e-14);
    EXPECT_EQ(s.pid.derivative, fuzzypid::pid::DerivativeSource::Observer);
    const std::vector<double> back = observed->from_spec(s);
    ASSERT_EQ(back.size(), x.size());
    EXPECT_NEAR(back.back(), std::log10(3.5), 1e-12);
    EXPECT_NEAR(back[back.size() - 2], std::log10(0.02), 1e-12);
    EXPECT_EQ(kept->to_spec(kept->from_spec(start)).pid.observer_bandwidth_hz, 1.0);
  }
  // A bandwidth is a frequency: at a 10 ms tick its box moves up by log10(5).
  const auto moved =
      tune::box_for_tick({{"observer_hz", -1.0, 1.0}}, named_family("pid"), 0.05, 0.01);
  EXPECT_NEAR(moved[0].log10_min, -1.0 + std::log10(5.0), 1e-12);
  EXPECT_NEAR(moved[0].log10_max, 1.0 + std::log10(5.0), 1e-12);
}

// --per-joint-bandwidth closes every family's space with "bandwidth_j2" .. "bandwidth_j6":
// log10 of joints 2-6's bandwidth scales relative to joint 1 (whose scale stays 1), in [-1, 1],
// written by to_spec and read back by from_spec; tf keeps its place. Without it the start's
// scales are kept; a start whose joint 1 is scaled is refused (its gains would not be joint 1's).
TEST(SearchBandwidth, FiveScalesCloseTheSpaceAndRoundTrip) {
  for (const controller::Family family : {named_family("pid"), named_family("scheduled"),
                                          named_family("fuzzy"), named_family("fuzzy-rules")}) {
    controller::ControllerSpec start = family == named_family("fuzzy-rules")
                                           ? converted(schedule(), named_family("fuzzy-rules"))
                                           : controller::paper_pid();
    start.bandwidth_scale = {1.0, 2.0, 0.5, 30.0, 1.0, 1.0};
    tune::TableOptions o;
    o.unvisited = tune::Unvisited::Free;
    std::string error;
    const auto filtered = tune::ParameterSpace::create(family, start, o, nullptr, error, true);
    const auto scaled = tune::ParameterSpace::create(family, start, o, nullptr, error, true, true);
    ASSERT_TRUE(filtered && scaled) << error;
    ASSERT_EQ(scaled->box().size(), filtered->box().size() + 5);
    for (std::size_t k = 0; k < filtered->box().size(); ++k)
      EXPECT_EQ(scaled->box()[k].name, filtered->box()[k].name);
    for (std::size_t j = 0; j < 5; ++j) {
      const tune::SearchBox& b = scaled->box()[filtered->box().size() + j];
      EXPECT_EQ(b.name, "bandwidth_j" + std::to_string(j + 2));
      EXPECT_EQ(b.log10_min, -1.0);
      EXPECT_EQ(b.log10_max, 1.0);
    }
    // The start enters with its scales, 30 clamped to the box's 10.
    std::vector<double> x = scaled->from_spec(start);
    const std::size_t first = filtered->box().size();
    EXPECT_NEAR(x[first], std::log10(2.0), 1e-15);
    EXPECT_NEAR(x[first + 1], std::log10(0.5), 1e-15);
    EXPECT_EQ(x[first + 2], 1.0);
    x[first + 3] = -0.25;
    const controller::ControllerSpec s = scaled->to_spec(x);
    EXPECT_EQ(s.bandwidth_scale[0], 1.0);
    EXPECT_NEAR(s.bandwidth_scale[4], std::pow(10.0, -0.25), 1e-15);
    EXPECT_EQ(s.bandwidth_scale[3], 10.0);
    EXPECT_EQ(s.gains.kp, filtered->to_spec(filtered->from_spec(start)).gains.kp);
    const std::vector<double> back = scaled->from_spec(s);
    ASSERT_EQ(back.size(), x.size());
    for (std::size_t k = 0; k < x.size(); ++k)
      EXPECT_NEAR(back[k], x[k], 1e-12) << scaled->box()[k].name;
    EXPECT_EQ(controller::validate(s), "");
    // Without the option the start's scales are kept.
    EXPECT_EQ(filtered->to_spec(filtered->from_spec(start)).bandwidth_scale, start.bandwidth_scale);
    start.bandwidth_scale[0] = 2.0;
    EXPECT_FALSE(tune::ParameterSpace::create(family, start, o, nullptr, error, true, true));
    EXPECT_NE(error.find("joint 1 has scale 1"), std::string::npos) << error;
  }
}
