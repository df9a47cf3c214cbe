// The table-driven zero-order Takagi-Sugeno engine (fuzzy/tsk_system.hpp): Eq. 8 and the weighted
// sum, firing-strength readout, the no-rule-fired path, and float against double.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <utility>

#include "fuzzypid/fuzzy/tsk_system.hpp"
#include "fuzzypid/paper.hpp"
#include "fuzzypid_support/uniform_real.hpp"

namespace {

using fuzzypid::Status;
using fuzzypid::fuzzy::Conjunction;
using fuzzypid::fuzzy::LinguisticVariable;
using fuzzypid::fuzzy::Term;
using fuzzypid::fuzzy::TskDefuzzifier;
using fuzzypid::fuzzy::TskSystem;
namespace paper = fuzzypid::paper;

constexpr Conjunction kConjunctions[] = {Conjunction::Minimum, Conjunction::Product};

// Brute force over all 49 rules with every term evaluated through Term::operator().
std::array<double, 3> brute_force(const paper::System<double>& s, double e, double ec,
                                  bool weighted_average) {
  std::array<double, 3> sum{};
  double total = 0.0;
  for (std::size_t i = 0; i < 7; ++i) {
    for (std::size_t j = 0; j < 7; ++j) {
      const double mu_e = s.e.term(i)(e);
      const double mu_ec = s.ec.term(j)(ec);
      const double w = s.conjunction == Conjunction::Minimum ? std::min(mu_e, mu_ec) : mu_e * mu_ec;
      total += w;
      for (std::size_t o = 0; o < 3; ++o)
        sum[o] += w * s.consequents[o][i][j];
    }
  }
  if (weighted_average)
    for (double& y : sum)
      y /= total;
  return sum;
}

TEST(TskSystem, WeightedAverageEqualsBruteForceOverAllRules) {
  const std::uint64_t seed = 31;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  fuzzypid::support::UniformReal<double> u(-0.4, 0.4);
  for (const auto conjunction : kConjunctions) {
    const auto s = paper::make_system<double>(conjunction);
    for (int k = 0; k < 10000; ++k) {
      const double e = u(rng);
      const double ec = u(rng);
      const auto r = s.infer(e, ec);
      const auto expected = brute_force(s, e, ec, true);
      ASSERT_EQ(r.status, Status::Ok);
      for (std::size_t o = 0; o < 3; ++o)
        ASSERT_NEAR(r.output[o], expected[o], 1e-15) << "e=" << e << " ec=" << ec;
    }
  }
}

// The supervisor form FuzzyPid calls every tick (no trace) and the traced form are one inference:
// the same outputs and status, including on peaks, outside the universe and for non-finite
// inputs, where the outputs are zero.
TEST(TskSystem, TheTickFormAndTheTracedFormGiveTheSameInference) {
  const std::uint64_t seed = 37;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  fuzzypid::support::UniformReal<double> u(-0.5, 0.5);
  std::uniform_int_distribution<int> peak(-3, 3);
  const double inf = std::numeric_limits<double>::infinity();
  for (const auto conjunction : kConjunctions) {
    for (const auto tables : {paper::Tables::Printed, paper::Tables::Corrected}) {
      const auto s = paper::make_system<double>(conjunction, tables);
      for (int k = 0; k < 20000; ++k) {
        double e = u(rng);
        double ec = u(rng);
        if (k % 5 == 0) e = 0.1 * peak(rng);
        if (k % 7 == 0) ec = 0.1 * peak(rng);
        if (k == 1) e = inf;
        if (k == 2) ec = std::numeric_limits<double>::quiet_NaN();
        const auto full = s.infer(e, ec);
        auto ws = s.make_workspace();
        std::array<double, 3> delta{1.0, 1.0, 1.0};
        const Status status = s.infer(e, ec, ws, delta);
        ASSERT_EQ(status, full.status) << "e=" << e << " ec=" << ec;
        for (std::size_t o = 0; o < 3; ++o)
          ASSERT_EQ(delta[o], full.output[o]) << "e=" << e << " ec=" << ec;
        if (status == Status::NonFiniteInput) {
          ASSERT_EQ(delta, (std::array<double, 3>{}));
        }
      }
    }
  }
}

TEST(TskSystem, WeightedSumIsTheWeightedAverageTimesTotalStrength) {
  const std::uint64_t seed = 32;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  fuzzypid::support::UniformReal<double> u(-0.4, 0.4);
  for (const auto conjunction : kConjunctions) {
    const auto average = paper::make_system<double>(conjunction);
    auto sum = average;
    sum.defuzzifier = TskDefuzzifier::WeightedSum;
    for (int k = 0; k < 5000; ++k) {
      const double e = u(rng);
      const double ec = u(rng);
      const auto ra = average.infer(e, ec);
      const auto rs = sum.infer(e, ec);
      const auto expected = brute_force(sum, e, ec, false);
      ASSERT_EQ(rs.total_strength, ra.total_strength);
      for (std::size_t o = 0; o < 3; ++o) {
        ASSERT_NEAR(rs.output[o], expected[o], 1e-15);
        ASSERT_NEAR(rs.output[o], ra.output[o] * ra.total_strength, 1e-15);
      }
    }
  }
}

TEST(TskSystem, ProductOnAPartitionOfUnityHasUnitTotalStrengthSoBothDefuzzifiersAgree) {
  const std::uint64_t seed = 33;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  fuzzypid::support::UniformReal<double> u(-0.3, 0.3);
  const auto average = paper::make_system<double>(Conjunction::Product);
  auto sum = average;
  sum.defuzzifier = TskDefuzzifier::WeightedSum;
  for (int k = 0; k < 5000; ++k) {
    const double e = u(rng);
    const double ec = u(rng);
    const auto ra = average.infer(e, ec);
    ASSERT_NEAR(ra.total_strength, 1.0, 1e-15);
    const auto rs = sum.infer(e, ec);
    for (std::size_t o = 0; o < 3; ++o)
      ASSERT_NEAR(rs.output[o], ra.output[o], 1e-15);
  }
}

TEST(TskSystem, WeightedSumByHandAtOnePoint) {
  // e = 0.05: ZE 0.5, PS 0.5; ec = -0.12: NM 0.2, NS 0.8 (see test_paper_system).
  auto s = paper::make_system<double>(Conjunction::Minimum);
  s.defuzzifier = TskDefuzzifier::WeightedSum;
  const auto r = s.infer(0.05, -0.12);
  const auto& kd = paper::kDeltaKdPrinted;
  EXPECT_NEAR(r.output[paper::kDeltaKd],
              0.2 * kd[3][1] + 0.5 * kd[3][2] + 0.2 * kd[4][1] + 0.5 * kd[4][2], 1e-15);
  EXPECT_NEAR(r.total_strength, 1.4, 1e-15);
}

TEST(TskSystem, FiringStrengthReadoutEqualsTheConjunctionOfDegrees) {
  const std::uint64_t seed = 34;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  fuzzypid::support::UniformReal<double> u(-0.4, 0.4);
  for (const auto conjunction : kConjunctions) {
    const auto s = paper::make_system<double>(conjunction);
    for (int k = 0; k < 2000; ++k) {
      const double e = u(rng);
      const double ec = u(rng);
      const auto r = s.infer(e, ec);
      EXPECT_EQ(r.conjunction, conjunction);
      double total = 0.0;
      int fired = 0;
      for (std::size_t i = 0; i < 7; ++i) {
        // Degrees from the position t = (e - min) / h by the precomputed 1/h, against the triangle
        // formulas: equal up to a few ulp of t (< 1e-14).
        ASSERT_NEAR(r.e.degree[i], s.e.term(i)(e), 1e-14);
        for (std::size_t j = 0; j < 7; ++j) {
          const double mu_e = s.e.term(i)(e);
          const double mu_ec = s.ec.term(j)(ec);
          const double expected =
              conjunction == Conjunction::Minimum ? std::min(mu_e, mu_ec) : mu_e * mu_ec;
          ASSERT_NEAR(r.firing_strength(i, j), expected, 1e-14) << "rule " << i << "," << j;
          total += r.firing_strength(i, j);
          fired += r.firing_strength(i, j) > 0.0;
        }
      }
      ASSERT_NEAR(r.total_strength, total, 1e-15);
      ASSERT_GE(fired, 1);
      ASSERT_LE(fired, 4);  // two adjacent sets per input at most
    }
  }
}

// Two inputs with a hole between their terms: values in (1, 2) belong to no set.
TskSystem<double, 2, 2, 2> gappy_system() {
  TskSystem<double, 2, 2, 2> s;
  const std::array<Term<double>, 2> terms{Term<double>::triangle(-1.0, 0.0, 1.0),
                                          Term<double>::triangle(2.0, 3.0, 4.0)};
  s.e = LinguisticVariable<double, 2>::custom(-1.0, 4.0, terms);
  s.ec = s.e;
  s.consequents[0] = {{{{1.0, 2.0}}, {{3.0, 4.0}}}};
  s.consequents[1] = {{{{-1.0, -2.0}}, {{-3.0, -4.0}}}};
  return s;
}

TEST(TskSystem, NoRuleFiredGivesZeroOutputsAndSaysSo) {
  for (const auto conjunction : kConjunctions) {
    for (const auto defuzzifier : {TskDefuzzifier::WeightedAverage, TskDefuzzifier::WeightedSum}) {
      auto s = gappy_system();
      s.conjunction = conjunction;
      s.defuzzifier = defuzzifier;
      ASSERT_TRUE(s.valid());
      for (const auto& [e, ec] : {std::pair{1.5, 0.0}, std::pair{0.0, 1.5}, std::pair{1.5, 1.5},
                                  std::pair{-7.0, 0.0}, std::pair{0.0, 10.0}}) {
        const auto r = s.infer(e, ec);
        EXPECT_EQ(r.status, Status::NoRuleFired) << "e=" << e << " ec=" << ec;
        EXPECT_EQ(r.output[0], 0.0);
        EXPECT_EQ(r.output[1], 0.0);
        EXPECT_EQ(r.total_strength, 0.0);
      }
      // Only rule (0, 1) fires, with strength 0.5 under either conjunction.
      const auto fired = s.infer(0.5, 3.0);
      const double scale = defuzzifier == TskDefuzzifier::WeightedAverage ? 1.0 : 0.5;
      EXPECT_EQ(fired.status, Status::Ok);
      EXPECT_EQ(fired.output[0], 2.0 * scale);
      EXPECT_EQ(fired.output[1], -2.0 * scale);
    }
  }
}

TEST(TskSystem, NonFiniteInputsGiveNonFiniteInputWithZeroOutputs) {
  const auto s = paper::make_system<double>();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const auto& [e, ec] : {std::pair{nan, 0.0}, std::pair{0.0, nan}, std::pair{inf, 0.0},
                              std::pair{0.0, -inf}, std::pair{nan, inf}}) {
    const auto r = s.infer(e, ec);
    EXPECT_EQ(r.status, Status::NonFiniteInput);
    for (double y : r.output)
      EXPECT_EQ(y, 0.0);
  }
}

TEST(TskSystem, ValidRejectsNonFiniteConsequentsAndBadVariables) {
  auto s = paper::make_system<double>();
  EXPECT_TRUE(s.valid());
  s.consequents[2][3][3] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(s.valid());
  auto t = paper::make_system<double>();
  t.ec = LinguisticVariable<double, 7>::uniform(1.0, -1.0);
  EXPECT_FALSE(t.valid());
}

TEST(TskSystem, NonSquareTablesIndexRowsByEAndColumnsByEc) {
  TskSystem<double, 3, 5, 1> s;
  s.e = LinguisticVariable<double, 3>::uniform(-1.0, 1.0);
  s.ec = LinguisticVariable<double, 5>::uniform(-2.0, 2.0);
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 5; ++j)
      s.consequents[0][i][j] = 10.0 * i + j;
  ASSERT_TRUE(s.valid());
  EXPECT_EQ(s.infer(1.0, -1.0).output[0], 21.0);
  EXPECT_EQ(s.infer(-1.0, 2.0).output[0], 4.0);
  EXPECT_NEAR(s.infer(0.5, 0.0).output[0], 0.5 * 12.0 + 0.5 * 22.0, 1e-15);
}

TEST(TskSystem, FloatInstantiationAgreesWithDouble) {
  const std::uint64_t seed = 35;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  fuzzypid::support::UniformReal<double> u(-0.4, 0.4);
  for (const auto conjunction : kConjunctions) {
    const auto sd = paper::make_system<double>(conjunction);
    const auto sf = paper::make_system<float>(conjunction);
    double max_difference = 0.0;
    for (int k = 0; k < 10000; ++k) {
      const float e = static_cast<float>(u(rng));
      const float ec = static_cast<float>(u(rng));
      const auto rd = sd.infer(e, ec);
      const auto rf = sf.infer(e, ec);
      ASSERT_EQ(rf.status, rd.status);
      for (std::size_t o = 0; o < 3; ++o) {
        // Outputs are at most 0.3 in size; float keeps ~7 significant digits through a handful
        // of operations.
        const double difference = std::fabs(static_cast<double>(rf.output[o]) - rd.output[o]);
        max_difference = std::max(max_difference, difference);
        ASSERT_LE(difference, 1e-6) << "e=" << e << " ec=" << ec;
      }
    }
    RecordProperty(
        std::string("float_vs_double_max_difference_") + fuzzypid::fuzzy::to_string(conjunction),
        std::to_string(max_difference));
  }
}

// locate() on random uniform partitions: the two degrees lie in [0, 1] and sum to 1, the interval
// index is in range, the edges and everything beyond them give exactly (1, 0) / (0, 1), and the
// degrees equal the triangle formulas of the variable's own terms up to rounding.
template <class Scalar, std::size_t N>
void expect_partition_of_unity(std::uint64_t seed) {
  SCOPED_TRACE("N = " + std::to_string(N) + ", seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  fuzzypid::support::UniformReal<double> center(-100.0, 100.0);
  fuzzypid::support::UniformReal<double> log_width(-3.0, 3.0);
  const Scalar rounding = Scalar(8 * N) * std::numeric_limits<Scalar>::epsilon();
  for (int v = 0; v < 200; ++v) {
    const double c = center(rng);
    const double w = std::pow(10.0, log_width(rng));
    const auto lv = LinguisticVariable<Scalar, N>::uniform(Scalar(c - w), Scalar(c + w));
    ASSERT_TRUE(lv.valid());
    const Scalar lo = lv.min();
    const Scalar hi = lv.max();
    fuzzypid::support::UniformReal<Scalar> x_of(lo - (hi - lo) / 4, hi + (hi - lo) / 4);
    for (int k = 0; k < 200; ++k) {
      const Scalar x = k == 0 ? lo : k == 1 ? hi : x_of(rng);
      const auto a = lv.locate(x);
      ASSERT_LE(a.k, N - 2);
      ASSERT_GE(a.lower, Scalar(0));
      ASSERT_GE(a.upper, Scalar(0));
      ASSERT_LE(a.lower, Scalar(1));
      ASSERT_LE(a.upper, Scalar(1));
      ASSERT_EQ(a.lower + a.upper, Scalar(1)) << "x = " << x;
      if (x <= lo) {
        ASSERT_EQ(a.k, 0u);
        ASSERT_EQ(a.lower, Scalar(1));
      }
      if (x >= hi && a.upper != Scalar(1)) {
        // t stopped a rounding short of the last peak: the next-to-last term keeps that much.
        ASSERT_EQ(a.k, N - 2);
        ASSERT_LE(a.lower, rounding);
      }
      const Scalar width = lv.centers()[a.k + 1] - lv.centers()[a.k];
      ASSERT_NEAR(a.lower, lv.term(a.k)(x), rounding * (Scalar(1) + std::fabs(lo) / width))
          << "x = " << x;
      ASSERT_NEAR(a.upper, lv.term(a.k + 1)(x), rounding * (Scalar(1) + std::fabs(lo) / width))
          << "x = " << x;
    }
  }
}

TEST(LinguisticVariable, UniformLocateIsAPartitionOfUnityEqualToTheTriangles) {
  expect_partition_of_unity<double, 2>(71);
  expect_partition_of_unity<double, 3>(72);
  expect_partition_of_unity<double, 7>(73);
  expect_partition_of_unity<double, 11>(74);
  expect_partition_of_unity<float, 7>(75);
  expect_partition_of_unity<float, 5>(76);
}

TEST(TskSystem, ValidAcceptsOnlyMinimumOrProductWithEitherTskDefuzzifier) {
  auto s = paper::make_system<double>(Conjunction::Product);
  EXPECT_TRUE(s.valid());
  s.defuzzifier = TskDefuzzifier::WeightedSum;
  EXPECT_TRUE(s.valid());
  for (const auto other :
       {Conjunction::BoundedDifference, Conjunction::DrasticProduct, Conjunction::EinsteinProduct,
        Conjunction::HamacherProduct, Conjunction::NilpotentMinimum}) {
    auto t = paper::make_system<double>();
    t.conjunction = other;
    EXPECT_FALSE(t.valid()) << fuzzypid::fuzzy::to_string(other);
  }
  auto u = paper::make_system<double>();
  u.defuzzifier = fuzzypid::fuzzy::Defuzzifier::Centroid;
  EXPECT_FALSE(u.valid());
}

}  // namespace
