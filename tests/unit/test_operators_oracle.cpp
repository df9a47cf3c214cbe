// Every membership function, hedge, t-norm and s-norm of fuzzy/membership.hpp and
// fuzzy/operators.hpp against fuzzylite 6 (tolerance macheps = 0) on thousands of points:
// parameters, peaks, edges, just beside them, outside the range, ±inf, huge values and random
// points. A NaN input is the one documented difference: fuzzylite returns NaN, fuzzypid 0.
#include <fl/Headers.h>
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "fuzzypid/fuzzy/membership.hpp"
#include "fuzzypid/fuzzy/operators.hpp"
#include "fuzzypid_support/uniform_real.hpp"

namespace {

using fuzzypid::fuzzy::Hedge;
using fuzzypid::fuzzy::Shape;
using fuzzypid::fuzzy::SNorm;
using fuzzypid::fuzzy::Term;
using fuzzypid::fuzzy::TNorm;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Case {
  const char* fl_class;
  std::vector<double> fl_params;  // fuzzylite's order (height last when given)
  Term<double> ours;
};

// Points around every parameter (exact, nextafter both ways, +-1e-9), a sweep, the far field.
std::vector<double> sample_points(const std::vector<double>& params, std::mt19937_64& rng) {
  std::vector<double> xs = {0.0, -0.0, kInf, -kInf, 1e300, -1e300, 1e-300};
  double lo = 0, hi = 0;
  for (double p : params) {
    if (!std::isfinite(p)) continue;
    lo = std::min(lo, p);
    hi = std::max(hi, p);
    for (double x : {p, std::nextafter(p, kInf), std::nextafter(p, -kInf), p + 1e-9, p - 1e-9})
      xs.push_back(x);
  }
  for (std::size_t a = 0; a < params.size(); ++a)
    for (std::size_t b = a + 1; b < params.size(); ++b)
      if (std::isfinite(params[a]) && std::isfinite(params[b]))
        xs.push_back((params[a] + params[b]) / 2);
  const double span = hi - lo + 1.0;
  fuzzypid::support::UniformReal<double> u(lo - span, hi + span);
  for (int k = 0; k < 2000; ++k)
    xs.push_back(u(rng));
  for (int k = 0; k <= 200; ++k)
    xs.push_back(lo - span + 3 * span * k / 200.0);
  return xs;
}

std::string join(const std::vector<double>& v) {
  std::ostringstream s;
  s.precision(17);
  for (double x : v)
    s << x << " ";
  return s.str();
}

TEST(OperatorsOracle, EveryMembershipFunctionEqualsFuzzylite) {
  fl::fuzzylite::setMachEps(0.0);
  using T = Term<double>;
  const double pts[] = {-1, 0, 0.5, 0.5, 1, 1, 3, 0};  // Discrete pairs for the pool
  const std::vector<Case> cases = {
      {"Triangle", {-1, 0, 2}, T::make(Shape::Triangle, -1, 0, 2)},
      {"Triangle", {-1, 0, 2, 0.5}, T::make(Shape::Triangle, -1, 0, 2, 0, 0.5)},
      {"Triangle", {0, 0, 1}, T::make(Shape::Triangle, 0, 0, 1)},
      {"Triangle", {0, 1, 1}, T::make(Shape::Triangle, 0, 1, 1)},
      {"Triangle", {-kInf, 0, 1}, T::make(Shape::Triangle, -kInf, 0, 1)},
      {"Trapezoid", {-1, 0, 1, 3}, T::make(Shape::Trapezoid, -1, 0, 1, 3)},
      {"Trapezoid", {-kInf, -kInf, 1, 3}, T::make(Shape::Trapezoid, -kInf, -kInf, 1, 3)},
      {"Trapezoid", {-1, 0, kInf, kInf, 0.7}, T::make(Shape::Trapezoid, -1, 0, kInf, kInf, 0.7)},
      {"Trapezoid", {0, 0, 1, 1}, T::make(Shape::Trapezoid, 0, 0, 1, 1)},
      {"Rectangle", {-0.5, 0.5}, T::make(Shape::Rectangle, -0.5, 0.5)},
      {"Rectangle", {-0.5, 0.5, 0.3}, T::make(Shape::Rectangle, -0.5, 0.5, 0, 0, 0.3)},
      {"Gaussian", {0.2, 0.3}, T::make(Shape::Gaussian, 0.2, 0.3)},
      {"Gaussian", {0.2, 0.3, 0.9}, T::make(Shape::Gaussian, 0.2, 0.3, 0, 0, 0.9)},
      {"GaussianProduct",
       {-0.2, 0.3, 0.4, 0.1},
       T::make(Shape::GaussianProduct, -0.2, 0.3, 0.4, 0.1)},
      {"GaussianProduct",
       {0.4, 0.3, -0.2, 0.1},
       T::make(Shape::GaussianProduct, 0.4, 0.3, -0.2, 0.1)},
      // Bell: fuzzylite (center, width, slope); ours p = {width, slope, center}.
      {"Bell", {0.5, 2, 3}, T::make(Shape::Bell, 2, 3, 0.5)},
      {"Bell", {0.5, 2, 0.5, 0.8}, T::make(Shape::Bell, 2, 0.5, 0.5, 0, 0.8)},
      {"PiShape", {-1, 0, 1, 3}, T::make(Shape::PiShape, -1, 0, 1, 3)},
      {"PiShape", {-1, 0, 0, 3, 0.5}, T::make(Shape::PiShape, -1, 0, 0, 3, 0.5)},
      {"SShape", {-1, 2}, T::make(Shape::SShape, -1, 2)},
      {"SShape", {-1, 2, 0.25}, T::make(Shape::SShape, -1, 2, 0, 0, 0.25)},
      {"ZShape", {-1, 2}, T::make(Shape::ZShape, -1, 2)},
      {"Sigmoid", {0.5, 10}, T::make(Shape::Sigmoid, 0.5, 10)},
      {"Sigmoid", {0.5, -4, 0.6}, T::make(Shape::Sigmoid, 0.5, -4, 0, 0, 0.6)},
      {"SigmoidDifference", {-1, 5, 3, 1}, T::make(Shape::SigmoidDifference, -1, 5, 3, 1)},
      {"SigmoidDifference", {1, 5, 3, -1}, T::make(Shape::SigmoidDifference, 1, 5, 3, -1)},
      {"SigmoidProduct", {-1, 5, -3, 1}, T::make(Shape::SigmoidProduct, -1, 5, -3, 1)},
      {"Ramp", {-1, 2}, T::make(Shape::Ramp, -1, 2)},
      {"Ramp", {2, -1, 0.5}, T::make(Shape::Ramp, 2, -1, 0, 0, 0.5)},
      {"Ramp", {1, 1}, T::make(Shape::Ramp, 1, 1)},
      {"Cosine", {0.5, 2}, T::make(Shape::Cosine, 0.5, 2)},
      {"Cosine", {0.5, 2, 0.4}, T::make(Shape::Cosine, 0.5, 2, 0, 0, 0.4)},
      {"Concave", {0.5, 1}, T::make(Shape::Concave, 0.5, 1)},
      {"Concave", {1, 0.5, 0.9}, T::make(Shape::Concave, 1, 0.5, 0, 0, 0.9)},
      {"Spike", {0.5, 2}, T::make(Shape::Spike, 0.5, 2)},
      {"Binary", {0.5, kInf}, T::make(Shape::Binary, 0.5, kInf)},
      {"Binary", {0.5, -kInf, 0.3}, T::make(Shape::Binary, 0.5, -kInf, 0, 0, 0.3)},
  };
  std::mt19937_64 rng(7);
  std::size_t points = 0;
  double worst = 0;
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(c.fl_class) + " " + join(c.fl_params));
    std::unique_ptr<fl::Term> oracle(
        fl::FactoryManager::instance()->term()->constructObject(c.fl_class));
    oracle->configure(join(c.fl_params));
    for (double x : sample_points(c.fl_params, rng)) {
      const double expected = oracle->membership(x);
      const double got = c.ours(x);
      ++points;
      if (std::isnan(expected)) {
        ADD_FAILURE() << "fuzzylite NaN at " << x;
        continue;
      }
      worst = std::max(worst, std::fabs(got - expected));
      ASSERT_EQ(got, expected) << "at x = " << x;
    }
    EXPECT_EQ(c.ours(kNaN), 0.0);
    EXPECT_TRUE(std::isnan(oracle->membership(kNaN)));
  }
  // Discrete: the points live in a pool the term refers to.
  {
    Term<double> ours{Shape::Discrete, {}, 1.0, 0, 4};
    std::unique_ptr<fl::Term> oracle(
        fl::FactoryManager::instance()->term()->constructObject("Discrete"));
    oracle->configure("-1 0 0.5 0.5 1 1 3 0");
    for (double x : sample_points({-1, 0.5, 1, 3}, rng)) {
      ++points;
      ASSERT_EQ(ours(x, pts), oracle->membership(x)) << "Discrete at " << x;
    }
  }
  std::cout << cases.size() + 1 << " terms, " << points
            << " points: max |ours - fuzzylite| = " << worst << "\n";
}

std::vector<double> degrees(std::mt19937_64& rng) {
  std::vector<double> v = {0.0, 1.0, 0.5, 0.25, 0.75, 1e-300, 1 - 1e-16, 0.1, 0.9, 0.3, 0.7};
  fuzzypid::support::UniformReal<double> u(0.0, 1.0);
  for (int k = 0; k < 150; ++k)
    v.push_back(u(rng));
  return v;
}

TEST(OperatorsOracle, EveryNormEqualsFuzzylite) {
  fl::fuzzylite::setMachEps(0.0);
  std::mt19937_64 rng(8);
  const auto d = degrees(rng);
  std::size_t n = 0;
  for (int k = 0; k < 7; ++k) {
    const auto t = static_cast<TNorm>(k);
    std::unique_ptr<fl::TNorm> oracle(fl::FactoryManager::instance()->tnorm()->constructObject(
        fuzzypid::fuzzy::names(t).fuzzylite));
    ASSERT_TRUE(oracle) << fuzzypid::fuzzy::names(t).fuzzylite;
    for (double a : d)
      for (double b : d) {
        ++n;
        ASSERT_EQ(fuzzypid::fuzzy::apply(t, a, b), oracle->compute(a, b))
            << oracle->className() << "(" << a << ", " << b << ")";
      }
  }
  for (int k = 0; k < 9; ++k) {
    const auto s = static_cast<SNorm>(k);
    std::unique_ptr<fl::SNorm> oracle(fl::FactoryManager::instance()->snorm()->constructObject(
        fuzzypid::fuzzy::names(s).fuzzylite));
    ASSERT_TRUE(oracle) << fuzzypid::fuzzy::names(s).fuzzylite;
    for (double a : d)
      for (double b : d) {
        ++n;
        ASSERT_EQ(fuzzypid::fuzzy::apply(s, a, b), oracle->compute(a, b))
            << oracle->className() << "(" << a << ", " << b << ")";
      }
  }
  std::cout << "16 norms, " << n << " pairs: all equal to fuzzylite\n";
}

TEST(OperatorsOracle, EveryHedgeEqualsFuzzylite) {
  fl::fuzzylite::setMachEps(0.0);
  std::mt19937_64 rng(9);
  std::size_t n = 0;
  for (int k = 0; k < 6; ++k) {
    const auto h = static_cast<Hedge>(k);
    std::unique_ptr<fl::Hedge> oracle(
        fl::FactoryManager::instance()->hedge()->constructObject(fuzzypid::fuzzy::to_string(h)));
    ASSERT_TRUE(oracle) << fuzzypid::fuzzy::to_string(h);
    for (double x : degrees(rng)) {
      ++n;
      ASSERT_EQ(fuzzypid::fuzzy::apply(h, x), oracle->hedge(x))
          << oracle->name() << "(" << x << ")";
    }
  }
  std::cout << "6 hedges, " << n << " degrees: all equal to fuzzylite\n";
}

TEST(OperatorsOracle, NamesParseBackInEveryNaming) {
  using fuzzypid::fuzzy::Naming;
  for (int k = 0; k < 7; ++k) {
    for (const Naming naming : {Naming::Fuzzylite, Naming::Fis, Naming::Fcl}) {
      TNorm t{};
      const auto& n = fuzzypid::fuzzy::kTNormNames[k];
      const char* name = naming == Naming::Fuzzylite ? n.fuzzylite
                         : naming == Naming::Fis     ? n.fis
                                                     : n.fcl;
      ASSERT_TRUE(fuzzypid::fuzzy::parse(name, naming, t));
      EXPECT_EQ(static_cast<int>(t), k);
    }
  }
  TNorm t{};
  EXPECT_FALSE(fuzzypid::fuzzy::parse("Maximum", Naming::Fuzzylite, t));
  SNorm s{};
  EXPECT_TRUE(fuzzypid::fuzzy::parse("probor", Naming::Fis, s));
  EXPECT_EQ(s, SNorm::AlgebraicSum);
  EXPECT_STREQ(fuzzypid::fuzzy::to_string(TNorm::Minimum), "min");
  EXPECT_STREQ(fuzzypid::fuzzy::to_string(TNorm::EinsteinProduct), "EinsteinProduct");
}

}  // namespace
