// The paper's supervisor (Tables 2-4, Eq. 8) checked against fuzzylite 6 as an independent oracle.
//
// fuzzylite is built here as the zero-order Takagi-Sugeno system the paper describes: inputs e, ec
// on [-0.3, 0.3] with shoulders NL = Trapezoid(-inf, -inf, -0.3, -0.2) and
// PL = Trapezoid(0.2, 0.3, inf, inf) and triangles NM..PM; one Constant output term per distinct
// table value; aggregation none (every rule keeps its own activation); WeightedAverage. Its
// comparison tolerance macheps is set to 0, otherwise fuzzylite snaps degrees within 1e-6 of a
// peak and drops rules weaker than 1e-6. fuzzylite is used in tests only.
#include <fl/Headers.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "fuzzypid/paper.hpp"
#include "fuzzypid_support/uniform_real.hpp"

namespace {

using fuzzypid::Status;
using fuzzypid::fuzzy::Conjunction;
namespace paper = fuzzypid::paper;

constexpr double kTolerance = 1e-12;
constexpr std::uint64_t kSeed = 0x5eed0f1a2b3c4d5eULL;
constexpr int kRandomPoints = 20000;

const char* const kOutputNames[3] = {"dKp", "dKi", "dKd"};

// The paper's system in fuzzylite, with Minimum or AlgebraicProduct as the AND operator.
std::unique_ptr<fl::Engine> make_fuzzylite_engine(Conjunction conjunction) {
  auto engine = std::make_unique<fl::Engine>("tao_deburring");
  for (const char* name : {"e", "ec"}) {
    auto* in = new fl::InputVariable(name, -0.3, 0.3);
    in->setLockValueInRange(false);
    in->addTerm(new fl::Trapezoid("NL", -fl::inf, -fl::inf, -0.3, -0.2));
    in->addTerm(new fl::Triangle("NM", -0.3, -0.2, -0.1));
    in->addTerm(new fl::Triangle("NS", -0.2, -0.1, 0.0));
    in->addTerm(new fl::Triangle("ZE", -0.1, 0.0, 0.1));
    in->addTerm(new fl::Triangle("PS", 0.0, 0.1, 0.2));
    in->addTerm(new fl::Triangle("PM", 0.1, 0.2, 0.3));
    in->addTerm(new fl::Trapezoid("PL", 0.2, 0.3, fl::inf, fl::inf));
    engine->addInputVariable(in);
  }

  const paper::Table* tables[3] = {&paper::kDeltaKpPrinted, &paper::kDeltaKiPrinted,
                                   &paper::kDeltaKdPrinted};
  // term_name[o][value] names the Constant term holding that table value.
  std::map<double, std::string> term_name[3];
  for (std::size_t o = 0; o < 3; ++o) {
    auto* out = new fl::OutputVariable(kOutputNames[o], -0.3, 0.3);
    out->setLockValueInRange(false);
    out->setLockPreviousValue(false);
    out->setDefaultValue(fl::nan);
    out->setAggregation(fl::null);
    out->setDefuzzifier(new fl::WeightedAverage("TakagiSugeno"));
    for (const auto& row : *tables[o]) {
      for (double value : row) {
        if (term_name[o].count(value) != 0) continue;
        const std::string name = "c" + std::to_string(term_name[o].size());
        term_name[o][value] = name;
        out->addTerm(new fl::Constant(name, value));
      }
    }
    engine->addOutputVariable(out);
  }

  auto* rules = new fl::RuleBlock("tables_2_to_4");
  if (conjunction == Conjunction::Minimum) {
    rules->setConjunction(new fl::Minimum);
  } else {
    rules->setConjunction(new fl::AlgebraicProduct);
  }
  rules->setDisjunction(fl::null);
  rules->setImplication(fl::null);
  rules->setActivation(new fl::General);
  for (std::size_t i = 0; i < paper::kNumTerms; ++i) {
    for (std::size_t j = 0; j < paper::kNumTerms; ++j) {
      std::ostringstream rule;
      rule << "if e is " << paper::kTermNames[i] << " and ec is " << paper::kTermNames[j]
           << " then";
      for (std::size_t o = 0; o < 3; ++o)
        rule << (o == 0 ? " " : " and ") << kOutputNames[o] << " is "
             << term_name[o].at((*tables[o])[i][j]);
      rules->addRule(fl::Rule::parse(rule.str(), engine.get()));
    }
  }
  engine->addRuleBlock(rules);
  return engine;
}

// The test points: random values in and beyond the universe, the exact term peaks (as written in
// the paper and as computed by fuzzypid), exact feet, and far-away values.
std::vector<std::pair<double, double>> make_points(std::mt19937_64& rng) {
  std::vector<double> special;
  for (int k = -3; k <= 3; ++k)
    special.push_back(0.1 * k);
  const auto system = paper::make_system<double>();
  for (double c : system.e.centers())
    special.push_back(c);
  for (double x : {-0.3, -0.2, -0.1, 0.0, 0.1, 0.2, 0.3}) {
    special.push_back(std::nextafter(x, -1.0));
    special.push_back(std::nextafter(x, 1.0));
  }
  for (double x : {-1e9, -2.5, -0.30000000001, 0.30000000001, 0.75, 1e9, 1e-300, -1e-300})
    special.push_back(x);

  std::vector<std::pair<double, double>> points;
  for (double e : special)
    for (double ec : special)
      points.emplace_back(e, ec);

  fuzzypid::support::UniformReal<double> inside(-0.3, 0.3);
  fuzzypid::support::UniformReal<double> wide(-0.6, 0.6);
  std::uniform_int_distribution<std::size_t> pick(0, special.size() - 1);
  for (int k = 0; k < kRandomPoints; ++k) {
    switch (k % 4) {
      case 0:
        points.emplace_back(inside(rng), inside(rng));
        break;
      case 1:
        points.emplace_back(wide(rng), wide(rng));
        break;
      case 2:
        points.emplace_back(special[pick(rng)], inside(rng));
        break;
      default:
        points.emplace_back(wide(rng), special[pick(rng)]);
        break;
    }
  }
  return points;
}

class FuzzyliteOracle : public ::testing::TestWithParam<Conjunction> {
 protected:
  void SetUp() override { fl::fuzzylite::setMachEps(0.0); }
};

TEST_P(FuzzyliteOracle, PaperSystemEqualsFuzzyliteEverywhere) {
  const Conjunction conjunction = GetParam();
  const auto system = paper::make_system<double>(conjunction);
  const auto engine = make_fuzzylite_engine(conjunction);
  std::string status;
  ASSERT_TRUE(engine->isReady(&status)) << status;

  std::mt19937_64 rng(kSeed);
  SCOPED_TRACE("seed " + std::to_string(kSeed));
  const auto points = make_points(rng);
  ASSERT_GE(points.size(), 10000u);

  fl::InputVariable* e_in = engine->getInputVariable("e");
  fl::InputVariable* ec_in = engine->getInputVariable("ec");
  double max_difference[3] = {0.0, 0.0, 0.0};
  for (const auto& [e, ec] : points) {
    e_in->setValue(e);
    ec_in->setValue(ec);
    engine->process();
    const auto r = system.infer(e, ec);
    ASSERT_EQ(r.status, Status::Ok) << "e=" << e << " ec=" << ec;
    for (std::size_t o = 0; o < 3; ++o) {
      const double expected = engine->getOutputVariable(o)->getValue();
      ASSERT_TRUE(std::isfinite(expected)) << "fuzzylite gave no value at e=" << e << " ec=" << ec;
      const double difference = std::fabs(r.output[o] - expected);
      max_difference[o] = std::max(max_difference[o], difference);
      ASSERT_LE(difference, kTolerance)
          << kOutputNames[o] << " at e=" << e << " ec=" << ec << ": fuzzypid " << r.output[o]
          << ", fuzzylite " << expected;
    }
  }

  const double overall = std::max({max_difference[0], max_difference[1], max_difference[2]});
  std::ostringstream figure;
  figure.precision(3);
  figure << std::scientific << overall;
  RecordProperty("conjunction", fuzzypid::fuzzy::to_string(conjunction));
  RecordProperty("points", static_cast<int>(points.size()));
  RecordProperty("max_abs_difference", figure.str());
  std::cout << "[ oracle   ] conjunction=" << fuzzypid::fuzzy::to_string(conjunction)
            << " points=" << points.size() << " seed=" << kSeed
            << " max|fuzzypid - fuzzylite| = " << figure.str() << " (dKp " << max_difference[0]
            << ", dKi " << max_difference[1] << ", dKd " << max_difference[2] << ")\n";
}

TEST_P(FuzzyliteOracle, FiringStrengthsEqualFuzzyliteRuleActivations) {
  const Conjunction conjunction = GetParam();
  const auto system = paper::make_system<double>(conjunction);
  const auto engine = make_fuzzylite_engine(conjunction);
  std::mt19937_64 rng(kSeed + 1);
  SCOPED_TRACE("seed " + std::to_string(kSeed + 1));
  fuzzypid::support::UniformReal<double> wide(-0.4, 0.4);
  const fl::RuleBlock* block = engine->getRuleBlock(0);
  for (int k = 0; k < 500; ++k) {
    const double e = wide(rng);
    const double ec = wide(rng);
    engine->setInputValue("e", e);
    engine->setInputValue("ec", ec);
    engine->process();
    const auto r = system.infer(e, ec);
    for (std::size_t i = 0; i < paper::kNumTerms; ++i) {
      for (std::size_t j = 0; j < paper::kNumTerms; ++j) {
        const fl::Rule* rule = block->getRule(i * paper::kNumTerms + j);
        EXPECT_NEAR(r.firing_strength(i, j), rule->getActivationDegree(), kTolerance)
            << "rule (" << i << ", " << j << ") at e=" << e << " ec=" << ec;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Conjunctions, FuzzyliteOracle,
                         ::testing::Values(Conjunction::Minimum, Conjunction::Product),
                         [](const ::testing::TestParamInfo<Conjunction>& info) {
                           return std::string(info.param == Conjunction::Minimum ? "Minimum"
                                                                                 : "Product");
                         });

}  // namespace
