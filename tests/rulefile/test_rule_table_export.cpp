// rulefile::rule_table_to_fll/fcl/fis: a supervisor::RuleTable written as a rule file evaluates, in
// fuzzypid's own reader and engine and in fuzzylite 6 (oracle, tests only), to RuleTable::infer's
// delta on seeded random tables, partitions, ratios and inputs inside and outside the universe.
#include <fl/Headers.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <tuple>

#include "fuzzypid/fuzzy/engine.hpp"
#include "fuzzypid/rulefile/rule_file.hpp"
#include "fuzzypid/rulefile/rule_table_export.hpp"
#include "fuzzypid/supervisor/engine_supervisor.hpp"
#include "fuzzypid/supervisor/fuzzy_pid.hpp"
#include "fuzzypid_support/uniform_real.hpp"

namespace {

using fuzzypid::Status;
using fuzzypid::fuzzy::Engine;
using fuzzypid::rulefile::LoadError;
using fuzzypid::rulefile::Model;
using fuzzypid::supervisor::RuleTable;

enum class Format { Fll, Fcl, Fis };
const char* name(Format f) {
  return f == Format::Fll ? "fll" : f == Format::Fcl ? "fcl" : "fis";
}

bool write(Format f, const RuleTable<double>& t, std::string& text, std::string& error) {
  switch (f) {
    case Format::Fll:
      return fuzzypid::rulefile::rule_table_to_fll(t, text, error);
    case Format::Fcl:
      return fuzzypid::rulefile::rule_table_to_fcl(t, text, error);
    case Format::Fis:
      return fuzzypid::rulefile::rule_table_to_fis(t, text, error);
  }
  return false;
}

std::unique_ptr<Model> load(Format f, const std::string& text) {
  auto model = std::make_unique<Model>();
  LoadError error;
  const bool ok = f == Format::Fll   ? fuzzypid::rulefile::parse_fll(text, "table", *model, error)
                  : f == Format::Fcl ? fuzzypid::rulefile::parse_fcl(text, "table", *model, error)
                                     : fuzzypid::rulefile::parse_fis(text, "table", *model, error);
  EXPECT_TRUE(ok) << error.to_string() << "\n" << text;
  return ok ? std::move(model) : nullptr;
}

std::unique_ptr<fl::Engine> load_fuzzylite(Format f, const std::string& text) {
  fl::Engine* e = f == Format::Fll   ? fl::FllImporter().fromString(text)
                  : f == Format::Fcl ? fl::FclImporter().fromString(text)
                                     : fl::FisImporter().fromString(text);
  return std::unique_ptr<fl::Engine>(e);
}

double uniform(std::mt19937_64& rng, double lo, double hi) {
  return fuzzypid::support::UniformReal<double>(lo, hi)(rng);
}

// Random symmetric ascending centers (c_max in [0.3, 4.2]), random T in [0.2, 3] (49 distinct
// values per gain), R in [0.2, 4] with each R set to 1 with probability 1/4 (no ramp for that
// gain), or all R = 1 when `unit_ratios`; `even` makes every table even in e (T[i][j] = T[6-i][j])
// with probability 1/2 and independently in ec, so that the writers merge mirrored rules.
RuleTable<double> random_table(std::mt19937_64& rng, bool unit_ratios, bool even = false) {
  RuleTable<double> t;
  for (auto* c : {&t.e_centers, &t.ec_centers}) {
    double v = 0.0;
    for (std::size_t k = 4; k < 7; ++k) {
      v += uniform(rng, 0.1, 1.4);
      (*c)[k] = v;
      (*c)[6 - k] = -v;
    }
  }
  for (auto& table : t.table)
    for (auto& row : table)
      for (auto& v : row)
        v = uniform(rng, 0.2, 3.0);
  if (even) {
    const bool in_e = std::uniform_int_distribution<int>(0, 1)(rng) == 1;
    const bool in_ec = std::uniform_int_distribution<int>(0, 1)(rng) == 1;
    for (auto& table : t.table)
      for (std::size_t i = 0; i < 7; ++i)
        for (std::size_t j = 0; j < 7; ++j)
          table[i][j] = table[in_e ? std::min(i, 6 - i) : i][in_ec ? std::min(j, 6 - j) : j];
  }
  for (auto& r : t.schedule_ratio)
    r = unit_ratios || std::uniform_int_distribution<int>(0, 3)(rng) == 0 ? 1.0
                                                                          : uniform(rng, 0.2, 4.0);
  return t;
}

// Inputs from well outside the universe (saturation) to its center, plus exact nodes and 0.
double random_input(std::mt19937_64& rng, const std::array<double, 7>& c) {
  const int kind = std::uniform_int_distribution<int>(0, 9)(rng);
  if (kind == 0) return c[std::uniform_int_distribution<std::size_t>(0, 6)(rng)];
  if (kind == 1) return 0.0;
  return uniform(rng, -2.0 * c[6] - 0.5, 2.0 * c[6] + 0.5);
}

struct Differences {
  double ours = 0.0;
  double fuzzylite = 0.0;
};

// Writes `tables` random tables in format f and compares the project's engine and fuzzylite with
// RuleTable::infer on `points` inputs each.
Differences compare(Format f, std::uint64_t seed, int tables, int points, bool even = false) {
  fl::fuzzylite::setMachEps(0.0);  // else fuzzylite snaps degrees within 1e-6 of 0 or 1
  std::mt19937_64 rng(seed);
  Differences worst;
  for (int n = 0; n < tables; ++n) {
    const RuleTable<double> t = random_table(rng, f == Format::Fis, even);
    EXPECT_TRUE(t.valid());
    std::string text, error;
    EXPECT_TRUE(write(f, t, text, error)) << error;
    const auto model = load(f, text);
    if (!model) return {INFINITY, INFINITY};
    auto engine = std::make_unique<Engine<double>>(*model);
    auto oracle = load_fuzzylite(f, text);
    std::string status;
    EXPECT_TRUE(oracle->isReady(&status)) << status;
    EXPECT_EQ(model->num_inputs, 2u);
    EXPECT_EQ(model->num_outputs, 3u);
    auto ws = t.make_workspace();
    for (int k = 0; k < points; ++k) {
      const double x = random_input(rng, t.e_centers), y = random_input(rng, t.ec_centers);
      std::array<double, 3> delta{};
      EXPECT_EQ(t.infer(x, y, ws, delta), Status::Ok);
      const double in[2] = {x, y};
      double out[3] = {};
      EXPECT_EQ(engine->evaluate(in, out), Status::Ok);
      oracle->getInputVariable(0)->setValue(x);
      oracle->getInputVariable(1)->setValue(y);
      oracle->process();
      for (std::size_t g = 0; g < 3; ++g) {
        const double ours = std::fabs(out[g] - delta[g]);
        const double theirs = std::fabs(oracle->getOutputVariable(g)->getValue() - delta[g]);
        worst.ours = std::max(worst.ours, std::isnan(ours) ? INFINITY : ours);
        worst.fuzzylite = std::max(worst.fuzzylite, std::isnan(theirs) ? INFINITY : theirs);
        if (!(ours <= 1e-12) || !(theirs <= 1e-9)) {
          ADD_FAILURE() << name(f) << " table " << n << " x=" << x << " y=" << y << " output " << g
                        << ": infer " << delta[g] << ", ours " << out[g] << ", fuzzylite "
                        << oracle->getOutputVariable(g)->getValue() << "\n"
                        << text;
          return {INFINITY, INFINITY};
        }
      }
    }
  }
  return worst;
}

TEST(RuleTableExport, FllEvaluatesToInferInOurReaderAndFuzzylite) {
  const std::uint64_t seed = 0xf11ULL;
  SCOPED_TRACE("seed " + std::to_string(seed));
  const Differences d = compare(Format::Fll, seed, 40, 2000);
  std::printf(".fll: largest |ours - infer| %.3g, |fuzzylite - infer| %.3g\n", d.ours, d.fuzzylite);
  EXPECT_LE(d.ours, 1e-12);
  EXPECT_LE(d.fuzzylite, 1e-9);
}

TEST(RuleTableExport, FclEvaluatesToInferInOurReaderAndFuzzylite) {
  const std::uint64_t seed = 0xfc1ULL;
  SCOPED_TRACE("seed " + std::to_string(seed));
  const Differences d = compare(Format::Fcl, seed, 40, 2000);
  std::printf(".fcl: largest |ours - infer| %.3g, |fuzzylite - infer| %.3g\n", d.ours, d.fuzzylite);
  EXPECT_LE(d.ours, 1e-12);
  EXPECT_LE(d.fuzzylite, 1e-9);
}

TEST(RuleTableExport, FisWithUnitRatiosEvaluatesToInferInOurReaderAndFuzzylite) {
  const std::uint64_t seed = 0xf15ULL;
  SCOPED_TRACE("seed " + std::to_string(seed));
  const Differences d = compare(Format::Fis, seed, 40, 2000);
  std::printf(".fis: largest |ours - infer| %.3g, |fuzzylite - infer| %.3g\n", d.ours, d.fuzzylite);
  EXPECT_LE(d.ours, 1e-12);
  EXPECT_LE(d.fuzzylite, 1e-9);
}

TEST(RuleTableExport, MirroredRulesOfEvenTablesMergeAndStayExact) {
  const std::uint64_t seed = 0xe7e4ULL;
  SCOPED_TRACE("seed " + std::to_string(seed));
  for (const Format f : {Format::Fll, Format::Fcl}) {
    const Differences d = compare(f, seed, 40, 2000, true);
    std::printf(".%s, even tables: largest |ours - infer| %.3g, |fuzzylite - infer| %.3g\n",
                name(f), d.ours, d.fuzzylite);
    EXPECT_LE(d.ours, 1e-12) << name(f);
    EXPECT_LE(d.fuzzylite, 1e-9) << name(f);
  }
  // A table even in both inputs: 4 x 4 rules per block instead of 7 x 7.
  RuleTable<double> t;
  t.schedule_ratio = {1.5, 1.5, 1.5};
  t.table[0][0][0] = t.table[0][6][0] = t.table[0][0][6] = t.table[0][6][6] = 0.85;
  std::string text, error;
  ASSERT_TRUE(fuzzypid::rulefile::rule_table_to_fll(t, text, error)) << error;
  const auto count = [&](const std::string& what) {
    std::size_t n = 0;
    for (std::size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1))
      ++n;
    return n;
  };
  EXPECT_EQ(count("  rule: "), 16u + 3u * 16u) << text;
  EXPECT_NE(text.find("rule: if (e is NB or e is PB) and (ec is NB or ec is PB) then dKp is "
                      "x0_85 and dKi is x1 and dKd is x1"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("rule: if e is ZO and (ec is NM or ec is PM) then"), std::string::npos);
  // The paper-style odd tables do not merge.
  t.table[0][0][0] = 0.9;
  ASSERT_TRUE(fuzzypid::rulefile::rule_table_to_fll(t, text, error)) << error;
  // Only dKi's and dKd's ramp rules merge: 12 of each gain's 16 pair e's sets.
  EXPECT_EQ(count("(e is N"), 2u * 12u) << text;
  EXPECT_EQ(count("  rule: "), 49u + 49u + 2u * 16u) << text;
}

TEST(RuleTableExport, TheLoadedFileDrivesFuzzyPidLikeTheTable) {
  // The family's use: S = K0. FuzzyPid on EngineSupervisor(loaded .fll) against FuzzyPid on the
  // RuleTable itself, over seeded ticks: gains within 1e-12 relative.
  using fuzzypid::supervisor::EngineSupervisor;
  using fuzzypid::supervisor::FuzzyPid;
  const std::uint64_t seed = 0xd41eULL;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  double worst = 0.0;
  for (int n = 0; n < 10; ++n) {
    const RuleTable<double> t = random_table(rng, false, n % 2 == 1);
    std::string text, error;
    ASSERT_TRUE(fuzzypid::rulefile::rule_table_to_fll(t, text, error)) << error;
    const auto model = load(Format::Fll, text);
    ASSERT_TRUE(model);
    const EngineSupervisor<double> supervisor(model.get());
    ASSERT_TRUE(supervisor.valid());
    fuzzypid::supervisor::FuzzyPidConfig<double> c;
    c.pid.gains = {uniform(rng, 1, 100), uniform(rng, 0, 10), uniform(rng, 0, 5)};
    c.output_scale = {c.pid.gains.kp, c.pid.gains.ki, c.pid.gains.kd};
    c.error_scale = uniform(rng, 1, 20);
    c.error_rate_scale = uniform(rng, 0.1, 5);
    FuzzyPid<double, RuleTable<double>> from_table(&t, c);
    auto from_file = std::make_unique<FuzzyPid<double, EngineSupervisor<double>>>(&supervisor, c);
    for (int k = 0; k < 500; ++k) {
      fuzzypid::pid::Input<double> in;
      in.setpoint = uniform(rng, -0.3, 0.3);
      in.setpoint_rate = uniform(rng, -1, 1);
      ASSERT_EQ(from_table.update(in, 0.001), Status::Ok);
      ASSERT_EQ(from_file->update(in, 0.001), Status::Ok);
      const auto& a = from_table.gains();
      const auto& b = from_file->gains();
      for (const auto& [ka, kb, k0] :
           {std::tuple{a.kp, b.kp, c.pid.gains.kp}, std::tuple{a.ki, b.ki, c.pid.gains.ki},
            std::tuple{a.kd, b.kd, c.pid.gains.kd}})
        worst = std::max(worst, std::fabs(ka - kb) / k0);
    }
  }
  std::printf("largest |K_file - K_table| / K0: %.3g\n", worst);
  EXPECT_LE(worst, 1e-12);
}

TEST(RuleTableExport, FisRefusesTheScheduleRampWhichItCannotExpress) {
  RuleTable<double> t;
  t.schedule_ratio[1] = 1.5;
  std::string text, error;
  EXPECT_FALSE(fuzzypid::rulefile::rule_table_to_fis(t, text, error));
  EXPECT_NE(error.find("ramp"), std::string::npos) << error;
  EXPECT_TRUE(fuzzypid::rulefile::rule_table_to_fll(t, text, error)) << error;
  EXPECT_TRUE(fuzzypid::rulefile::rule_table_to_fcl(t, text, error)) << error;
}

TEST(RuleTableExport, InvalidTablesAreRefusedInEveryFormat) {
  RuleTable<double> t;
  t.e_centers[6] = 2.0;  // asymmetric
  for (const Format f : {Format::Fll, Format::Fcl, Format::Fis}) {
    std::string text, error;
    EXPECT_FALSE(write(f, t, text, error)) << name(f);
    EXPECT_FALSE(error.empty()) << name(f);
  }
}

// A cell beyond the float range (1e300) is refused naming the cell and its value, in every format,
// instead of a file whose ramp term name does not parse; a large cell that floats hold (1e30) gets
// a ramp term whose name every reader takes, and the file loads.
TEST(RuleTableExport, ACellBeyondTheFloatRangeIsRefusedNamingTheCell) {
  RuleTable<double> t;
  t.schedule_ratio = {2.0, 1.0, 1.0};
  t.table[0][0][1] = 1e300;  // kp, e NB, ec NM
  for (const Format f : {Format::Fll, Format::Fcl, Format::Fis}) {
    std::string text, error;
    EXPECT_FALSE(write(f, t, text, error)) << name(f);
    EXPECT_NE(error.find("rule table Kp cell [0][1] (e NB, ec NM) is 1e+300, beyond the float"),
              std::string::npos)
        << name(f) << ": " << error;
  }
  t.table[0][0][1] = 1e30;
  for (const Format f : {Format::Fll, Format::Fcl}) {
    std::string text, error;
    ASSERT_TRUE(write(f, t, text, error)) << name(f) << ": " << error;
    EXPECT_NE(load(f, text), nullptr) << name(f);
    EXPECT_EQ(text.find("ramp_x1.2"), std::string::npos) << name(f);
  }
}

TEST(RuleTableExport, TermsAreNamedByTheRatioTheyStandFor) {
  EXPECT_EQ(fuzzypid::rulefile::ratio_term_name(0.85), "x0_85");
  EXPECT_EQ(fuzzypid::rulefile::ratio_term_name(1.0), "x1");
  EXPECT_EQ(fuzzypid::rulefile::ratio_term_name(1e-5), "x1em05");
  EXPECT_EQ(fuzzypid::rulefile::ratio_term_name(1.0 / 3.0),
            "x0_3333333333333333");  // shortest round trip

  RuleTable<double> t;
  t.schedule_ratio = {2.0, 1.0, 0.5};
  t.table[0][0][6] = 0.85;  // NB, PB
  t.table[2][3][3] = 1.25;  // ZO, ZO
  std::string text, error;
  ASSERT_TRUE(fuzzypid::rulefile::rule_table_to_fll(t, text, error)) << error;
  EXPECT_NE(text.find("term: x0_85 Constant -0.15"), std::string::npos) << text;
  EXPECT_NE(
      text.find("rule: if e is NB and ec is PB then dKp is x0_85 and dKi is x1 and dKd is x1"),
      std::string::npos)
      << text;
  // dKd's ramp: T up to 1.25 gives s = 2 and the constant (0.5 - 1) 2 = -1, weight 1.25 / 2.
  EXPECT_NE(text.find("term: ramp_x2 Constant -1"), std::string::npos) << text;
  EXPECT_NE(text.find("rule: if e is ZO and ec is ZO and (e is neg or e is pos or ec is neg or ec "
                      "is pos) then dKd is ramp_x2 with 0.625"),
            std::string::npos)
      << text;
  // Ki has R = 1: no ramp term and no ramp rule.
  EXPECT_EQ(text.find("then dKi is ramp"), std::string::npos) << text;
  EXPECT_NE(text.find("S = K0"), std::string::npos) << "the header states the output scale";
}

}  // namespace
