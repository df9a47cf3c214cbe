// The Mamdani path of the core (MamdaniSystem, defuzzify.hpp): against fuzzylite 6's Mamdani
// engine with Centroid at the same resolution, and the exact centroid against hand-computed
// areas and a very fine midpoint rule.
#include <fl/Headers.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <memory>
#include <random>
#include <string>

#include "fuzzypid/fuzzy/mamdani_system.hpp"
#include "fuzzypid/paper.hpp"

namespace {

using fuzzypid::Status;
using fuzzypid::fuzzy::Activation;
using fuzzypid::fuzzy::AggregatedSet;
using fuzzypid::fuzzy::Aggregation;
using fuzzypid::fuzzy::CentroidMethod;
using fuzzypid::fuzzy::Conjunction;
using fuzzypid::fuzzy::Implication;
using fuzzypid::fuzzy::LinguisticVariable;
using fuzzypid::fuzzy::Term;

constexpr std::size_t kN = 7;
constexpr std::size_t kTerms = 5;
using System = fuzzypid::fuzzy::MamdaniSystem<double, kN, kN, kTerms, 2>;

// Uniform in [lo, hi) from the top 53 bits: portable, unlike std::uniform_real_distribution.
double uniform(std::mt19937_64& rng, double lo, double hi) {
  return lo + (hi - lo) * static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

// Output 0: the paper's dKp table mapped onto five terms NB..PB on [-0.03, 0.03]; output 1: a
// pseudo-random table with empty cells over terms of every piecewise-linear shape on [0, 10].
System make_system(Conjunction conjunction, Implication implication, CentroidMethod centroid,
                   int resolution) {
  System s;
  s.e = LinguisticVariable<double, kN>::uniform(-0.3, 0.3);
  s.ec = s.e;
  s.outputs[0].min = -0.03;
  s.outputs[0].max = 0.03;
  s.outputs[0].terms = {
      Term<double>::left_shoulder(-0.03, -0.015), Term<double>::triangle(-0.03, -0.015, 0.0),
      Term<double>::triangle(-0.015, 0.0, 0.015), Term<double>::triangle(0.0, 0.015, 0.03),
      Term<double>::right_shoulder(0.015, 0.03)};
  s.outputs[1].min = 0.0;
  s.outputs[1].max = 10.0;
  s.outputs[1].terms = {
      Term<double>::trapezoid(-1.0, 0.0, 1.5, 4.0), Term<double>::triangle(1.0, 3.0, 4.5),
      Term<double>::trapezoid(3.0, 4.0, 6.0, 9.5), Term<double>::triangle(5.0, 8.0, 12.0),
      Term<double>::right_shoulder(7.5, 9.0)};
  std::uint32_t lcg = 12345;
  for (std::size_t i = 0; i < kN; ++i) {
    for (std::size_t j = 0; j < kN; ++j) {
      const double v = fuzzypid::paper::kDeltaKpPrinted[i][j];
      s.consequents[0][i][j] = static_cast<int>(std::lround(v / 0.015)) + 2;
      lcg = lcg * 1103515245u + 12345u;
      const int r = static_cast<int>((lcg >> 16) % 7);
      s.consequents[1][i][j] = r < 5 ? r : -1;
    }
  }
  s.conjunction = conjunction;
  s.implication = implication;
  s.centroid = centroid;
  s.resolution = resolution;
  return s;
}

fl::Term* to_fl(const std::string& name, const Term<double>& t) {
  using fuzzypid::fuzzy::Shape;
  const auto& p = t.p;
  switch (t.shape) {
    case Shape::Triangle:
      return new fl::Triangle(name, p[0], p[1], p[2]);
    case Shape::Trapezoid:
      return new fl::Trapezoid(name, p[0], p[1], p[2], p[3]);
    case Shape::LeftShoulder:
      return new fl::Trapezoid(name, -fl::inf, -fl::inf, p[0], p[1]);
    case Shape::RightShoulder:
      return new fl::Trapezoid(name, p[0], p[1], fl::inf, fl::inf);
    default:
      return nullptr;
  }
}

// The same system in fuzzylite: one rule per (cell, output), max aggregation, Centroid.
std::unique_ptr<fl::Engine> make_fuzzylite(const System& s, int resolution) {
  auto engine = std::make_unique<fl::Engine>("mamdani");
  const char* in_names[2] = {"e", "ec"};
  const LinguisticVariable<double, kN>* vars[2] = {&s.e, &s.ec};
  for (int v = 0; v < 2; ++v) {
    auto* in = new fl::InputVariable(in_names[v], -0.3, 0.3);
    in->setLockValueInRange(false);
    for (std::size_t k = 0; k < kN; ++k) {
      Term<double> t = vars[v]->term(k);
      in->addTerm(to_fl("T" + std::to_string(k), t));
    }
    engine->addInputVariable(in);
  }
  for (std::size_t o = 0; o < 2; ++o) {
    auto* out = new fl::OutputVariable("y" + std::to_string(o), s.outputs[o].min, s.outputs[o].max);
    out->setLockValueInRange(false);
    out->setLockPreviousValue(false);
    out->setDefaultValue(fl::nan);
    out->setAggregation(new fl::Maximum);
    out->setDefuzzifier(new fl::Centroid(resolution));
    for (std::size_t t = 0; t < kTerms; ++t)
      out->addTerm(to_fl("O" + std::to_string(t), s.outputs[o].terms[t]));
    engine->addOutputVariable(out);
  }
  auto* rules = new fl::RuleBlock("rules");
  rules->setConjunction(s.conjunction == Conjunction::Minimum
                            ? static_cast<fl::TNorm*>(new fl::Minimum)
                            : new fl::AlgebraicProduct);
  rules->setImplication(s.implication == Implication::Minimum
                            ? static_cast<fl::TNorm*>(new fl::Minimum)
                            : new fl::AlgebraicProduct);
  rules->setActivation(new fl::General);
  for (std::size_t o = 0; o < 2; ++o)
    for (std::size_t i = 0; i < kN; ++i)
      for (std::size_t j = 0; j < kN; ++j)
        if (s.consequents[o][i][j] >= 0)
          rules->addRule(fl::Rule::parse("if e is T" + std::to_string(i) + " and ec is T" +
                                             std::to_string(j) + " then y" + std::to_string(o) +
                                             " is O" + std::to_string(s.consequents[o][i][j]),
                                         engine.get()));
  engine->addRuleBlock(rules);
  return engine;
}

TEST(MamdaniSystem, EqualsFuzzyliteCentroidAtTheSameResolution) {
  fl::fuzzylite::setMachEps(0.0);
  constexpr std::uint64_t kSeed = 0x6d616d64616e6931ULL;
  std::cout << "seed " << kSeed << "\n";
  std::mt19937_64 rng(kSeed);
  double max_diff = 0.0;
  int empty = 0;
  for (const auto conjunction : {Conjunction::Minimum, Conjunction::Product}) {
    for (const auto implication : {Implication::Minimum, Implication::Product}) {
      for (const int resolution : {100, 1000}) {
        const System s = make_system(conjunction, implication, CentroidMethod::Sampled, resolution);
        ASSERT_TRUE(s.valid());
        auto fl_engine = make_fuzzylite(s, resolution);
        std::string status;
        ASSERT_TRUE(fl_engine->isReady(&status)) << status;
        for (int n = 0; n < 2500; ++n) {
          const double e = uniform(rng, -0.4, 0.4);
          const double ec = uniform(rng, -0.4, 0.4);
          fl_engine->setInputValue("e", e);
          fl_engine->setInputValue("ec", ec);
          fl_engine->process();
          const auto r = s.infer(e, ec);
          for (std::size_t o = 0; o < 2; ++o) {
            const double expected = fl_engine->getOutputVariable(o)->getValue();
            if (std::isnan(expected)) {
              ++empty;
              EXPECT_EQ(r.status, Status::NoRuleFired);
              EXPECT_EQ(r.output[o], 0.0);
              continue;
            }
            const double diff = std::fabs(r.output[o] - expected);
            max_diff = std::max(max_diff, diff);
            ASSERT_LE(diff, 1e-9) << "e=" << e << " ec=" << ec << " output " << o;
          }
        }
      }
    }
  }
  std::cout << "max |ours - fuzzylite| = " << max_diff << ", empty outputs " << empty << "\n";
  EXPECT_GT(empty, 0);  // the empty cells of output 1 are exercised
}

double exact_centroid(const Activation<double>* acts, std::size_t n, Implication imp,
                      Aggregation agg, double min, double max) {
  std::array<double, 64> bp{};
  std::array<double, 32> lines{};
  std::array<double, 64> cross{};
  const AggregatedSet<double> set{acts, n, imp, agg};
  return fuzzypid::fuzzy::centroid_exact(set, min, max, bp.data(), lines.data(), cross.data(),
                                         {bp.size(), lines.size(), cross.size()});
}

TEST(ExactCentroid, MatchesHandComputedAreas) {
  // A triangle fully activated: its centroid (a + b + c) / 3.
  const Term<double> tri = Term<double>::triangle(0.0, 0.0, 3.0);
  const Activation<double> full{&tri, 1.0};
  EXPECT_NEAR(exact_centroid(&full, 1, Implication::Minimum, Aggregation::Maximum, 0.0, 3.0), 1.0,
              1e-15);
  // Clipped at 0.5: a 1.5 x 0.5 rectangle (moment 0.5625) and a triangle from 1.5 to 3 (area
  // 0.375, centroid 2): 1.3125 / 1.125 = 7/6.
  const Activation<double> half{&tri, 0.5};
  EXPECT_NEAR(exact_centroid(&half, 1, Implication::Minimum, Aggregation::Maximum, 0.0, 3.0),
              7.0 / 6.0, 1e-15);
  // Scaled instead of clipped the shape is unchanged.
  EXPECT_NEAR(exact_centroid(&half, 1, Implication::Product, Aggregation::Maximum, 0.0, 3.0), 1.0,
              1e-15);
  // Two mirror-image terms: the envelope is symmetric about 1.5 whatever the overlap.
  const Term<double> a = Term<double>::triangle(0.0, 1.0, 2.0);
  const Term<double> b = Term<double>::triangle(1.0, 2.0, 3.0);
  const Activation<double> pair[2] = {{&a, 0.7}, {&b, 0.7}};
  for (const auto agg : {Aggregation::Maximum, Aggregation::Sum})
    for (const auto imp : {Implication::Minimum, Implication::Product})
      EXPECT_NEAR(exact_centroid(pair, 2, imp, agg, 0.0, 3.0), 1.5, 1e-15);
  // Range cuts the set: only [0, 1] of triangle(0, 1, 2) counts, centroid 2/3.
  const Activation<double> cut{&a, 1.0};
  EXPECT_NEAR(exact_centroid(&cut, 1, Implication::Minimum, Aggregation::Maximum, 0.0, 1.0),
              2.0 / 3.0, 1e-15);
  // No area in the range, and a non-piecewise-linear term: NaN.
  EXPECT_TRUE(
      std::isnan(exact_centroid(&cut, 1, Implication::Minimum, Aggregation::Maximum, 5.0, 6.0)));
  const Term<double> g = Term<double>::gaussian(0.0, 1.0);
  const Activation<double> gauss{&g, 1.0};
  EXPECT_TRUE(
      std::isnan(exact_centroid(&gauss, 1, Implication::Minimum, Aggregation::Maximum, -1.0, 1.0)));
}

TEST(ExactCentroid, AgreesWithAVeryFineMidpointRule) {
  constexpr std::uint64_t kSeed = 0x65786163745f6331ULL;
  std::cout << "seed " << kSeed << "\n";
  std::mt19937_64 rng(kSeed);
  double max_diff = 0.0;
  for (int n = 0; n < 150; ++n) {
    // Random piecewise-linear terms without vertical edges (a jump costs the midpoint rule O(dx)).
    std::array<Term<double>, 6> terms{};
    std::array<Activation<double>, 6> acts{};
    const std::size_t count = 1 + rng() % 6;
    for (std::size_t k = 0; k < count; ++k) {
      const double c = uniform(rng, -1.0, 11.0);
      const double w1 = uniform(rng, 0.2, 3.0);
      const double w2 = uniform(rng, 0.2, 3.0);
      switch (rng() % 4) {
        case 0:
          terms[k] = Term<double>::triangle(c - w1, c, c + w2);
          break;
        case 1:
          terms[k] = Term<double>::trapezoid(c - w1, c, c + 0.5 * w2, c + w1 + w2);
          break;
        case 2:
          terms[k] = Term<double>::left_shoulder(c, c + w1);
          break;
        default:
          terms[k] = Term<double>::right_shoulder(c - w1, c);
          break;
      }
      acts[k] = {&terms[k], uniform(rng, 0.05, 1.0)};
    }
    for (const auto agg : {Aggregation::Maximum, Aggregation::Sum}) {
      for (const auto imp : {Implication::Minimum, Implication::Product}) {
        const AggregatedSet<double> set{acts.data(), count, imp, agg};
        const double fine = fuzzypid::fuzzy::centroid_sampled(set, 0.0, 10.0, 200000);
        const double exact = exact_centroid(acts.data(), count, imp, agg, 0.0, 10.0);
        if (std::isnan(fine)) {
          EXPECT_TRUE(std::isnan(exact));
          continue;
        }
        max_diff = std::max(max_diff, std::fabs(exact - fine));
        ASSERT_NEAR(exact, fine, 1e-8) << "case " << n;
      }
    }
  }
  std::cout << "max |exact - midpoint(200000)| = " << max_diff << "\n";
}

TEST(MamdaniSystem, ExactCentroidApproachesTheSampledOneAsResolutionGrows) {
  const System exact =
      make_system(Conjunction::Minimum, Implication::Minimum, CentroidMethod::Exact, 0);
  const System fine =
      make_system(Conjunction::Minimum, Implication::Minimum, CentroidMethod::Sampled, 200000);
  ASSERT_TRUE(exact.valid());
  std::mt19937_64 rng(7);
  for (int n = 0; n < 50; ++n) {
    const double e = uniform(rng, -0.35, 0.35);
    const double ec = uniform(rng, -0.35, 0.35);
    const auto a = exact.infer(e, ec);
    const auto b = fine.infer(e, ec);
    ASSERT_EQ(a.status, b.status);
    // Output 0 has vertical edges only at the range ends; output 1 none inside the range.
    EXPECT_NEAR(a.output[0], b.output[0], 1e-9);
    EXPECT_NEAR(a.output[1], b.output[1], 1e-7);
  }
}

TEST(MamdaniSystem, ReportsActivationsFiringStrengthsAndFaults) {
  const System s =
      make_system(Conjunction::Minimum, Implication::Minimum, CentroidMethod::Exact, 0);
  // e = 0.05: ZE, PS 0.5 each; ec = 0: ZE 1. Rules (ZE, ZE) and (PS, ZE) fire at 0.5.
  const auto r = s.infer(0.05, 0.0);
  EXPECT_NEAR(r.firing_strength(3, 3), 0.5, 1e-15);
  EXPECT_NEAR(r.firing_strength(4, 3), 0.5, 1e-15);
  EXPECT_EQ(r.firing_strength(0, 0), 0.0);
  const int t = s.consequents[0][4][3];
  EXPECT_NEAR(r.activation[0][static_cast<std::size_t>(t)], 0.5, 1e-15);

  const auto bad = s.infer(std::nan(""), 0.0);
  EXPECT_EQ(bad.status, Status::NonFiniteInput);
  EXPECT_EQ(bad.output[0], 0.0);

  System invalid = s;
  invalid.outputs[1].terms[0] = Term<double>::gaussian(0.0, 1.0);
  EXPECT_FALSE(invalid.valid());  // exact centroid needs piecewise-linear terms
  invalid.centroid = CentroidMethod::Sampled;
  invalid.resolution = 100;
  EXPECT_TRUE(invalid.valid());
  invalid.consequents[0][0][0] = static_cast<int>(kTerms);
  EXPECT_FALSE(invalid.valid());
}

}  // namespace
