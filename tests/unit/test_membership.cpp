// Membership functions against their closed forms, run-time terms, and the linguistic variables
// built from them (the paper's input partition, section 5.1 and Fig. 4).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "fuzzypid/fuzzy/formula.hpp"
#include "fuzzypid/fuzzy/linguistic_variable.hpp"
#include "fuzzypid/fuzzy/membership.hpp"
#include "fuzzypid/paper.hpp"
#include "fuzzypid_support/uniform_real.hpp"

namespace {

using fuzzypid::fuzzy::Bell;
using fuzzypid::fuzzy::Gaussian;
using fuzzypid::fuzzy::LeftShoulder;
using fuzzypid::fuzzy::LinguisticVariable;
using fuzzypid::fuzzy::RightShoulder;
using fuzzypid::fuzzy::Shape;
using fuzzypid::fuzzy::Singleton;
using fuzzypid::fuzzy::Term;
using fuzzypid::fuzzy::Trapezoid;
using fuzzypid::fuzzy::Triangle;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// The piecewise-linear shapes are usable in constant expressions.
static_assert(Triangle<double>{0.0, 1.0, 2.0}(0.5) == 0.5);
static_assert(Triangle<double>{0.0, 1.0, 2.0}(1.0) == 1.0);
static_assert(Triangle<double>{0.0, 1.0, 2.0}(1.5) == 0.5);
static_assert(Triangle<double>{0.0, 1.0, 2.0}(0.0) == 0.0);
static_assert(Triangle<double>{0.0, 1.0, 2.0}(2.0) == 0.0);
static_assert(Triangle<double>{0.0, 1.0, 2.0}(kNaN) == 0.0);
static_assert(Triangle<double>{0.0, 0.0, 2.0}(0.0) == 1.0);  // vertical left edge
static_assert(Triangle<double>{0.0, 2.0, 2.0}(2.0) == 1.0);  // vertical right edge
static_assert(Trapezoid<double>{0.0, 1.0, 3.0, 4.0}(2.0) == 1.0);
static_assert(Trapezoid<double>{0.0, 1.0, 3.0, 4.0}(3.5) == 0.5);
static_assert(Trapezoid<double>{-kInf, -kInf, -0.3, -0.2}(-kInf) == 1.0);
static_assert(Trapezoid<double>{0.2, 0.3, kInf, kInf}(kInf) == 1.0);
static_assert(Trapezoid<double>{0.2, 0.3, kInf, kInf}(kNaN) == 0.0);
static_assert(LeftShoulder<double>{-1.0, 1.0}(0.0) == 0.5);
static_assert(LeftShoulder<double>{-1.0, 1.0}(-kInf) == 1.0);
static_assert(LeftShoulder<double>{-1.0, 1.0}(kNaN) == 0.0);
static_assert(RightShoulder<double>{-1.0, 1.0}(0.5) == 0.75);
static_assert(RightShoulder<double>{-1.0, 1.0}(kInf) == 1.0);
static_assert(RightShoulder<double>{-1.0, 1.0}(kNaN) == 0.0);
static_assert(Singleton<double>{0.25}(0.25) == 1.0);
static_assert(Singleton<double>{0.25}(0.2500001) == 0.0);
static_assert(Term<double>::triangle(0.0, 1.0, 2.0).center() == 1.0);
static_assert(Term<double>::trapezoid(0.0, 1.0, 3.0, 4.0).center() == 2.0);
static_assert(Term<double>::triangle(0.0, 1.0, 2.0).valid());
static_assert(!Term<double>::triangle(2.0, 1.0, 0.0).valid());
static_assert(Triangle<float>{0.0f, 1.0f, 2.0f}(0.25f) == 0.25f);
static_assert(LinguisticVariable<double, 7>::uniform(-0.3, 0.3).valid());
static_assert(!LinguisticVariable<double, 7>::uniform(0.3, -0.3).valid());

struct Case {
  double x;
  double expected;
};

std::string describe(double x) {
  return "x = " + std::to_string(x) + (x != x ? " (NaN)" : "");
}

TEST(Triangle, MatchesItsClosedFormIncludingEdgesNaNAndInfinity) {
  const Triangle<double> t{-1.0, 0.5, 2.0};
  const Case cases[] = {
      {-1.0, 0.0},           {2.0, 0.0},   {0.5, 1.0}, {-0.25, 0.5},
      {1.25, 0.5},           {-5.0, 0.0},  {5.0, 0.0}, {kNaN, 0.0},
      {kInf, 0.0},           {-kInf, 0.0}, {0.2, 0.8}, {1.7, 0.2},
      {-0.999, 0.001 / 1.5},
  };
  for (const auto& c : cases)
    EXPECT_NEAR(t(c.x), c.expected, 1e-15) << describe(c.x);
}

TEST(Triangle, MatchesTheMinOfItsTwoLinesOnRandomPoints) {
  const std::uint64_t seed = 11;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  fuzzypid::support::UniformReal<double> u(-3.0, 3.0);
  for (int k = 0; k < 10000; ++k) {
    double p[3] = {u(rng), u(rng), u(rng)};
    std::sort(p, p + 3);
    if (!(p[0] < p[1] && p[1] < p[2])) continue;
    const Triangle<double> t{p[0], p[1], p[2]};
    const double x = u(rng);
    const double closed =
        std::max(0.0, std::min((x - p[0]) / (p[1] - p[0]), (p[2] - x) / (p[2] - p[1])));
    ASSERT_NEAR(t(x), closed, 1e-12) << describe(x);
  }
}

TEST(Triangle, DegenerateVerticalEdgesJumpToOneAtThePeak) {
  const Triangle<double> left{0.0, 0.0, 1.0};
  EXPECT_EQ(left(0.0), 1.0);
  EXPECT_EQ(left(-1e-300), 0.0);
  EXPECT_EQ(left(0.25), 0.75);
  EXPECT_EQ(left(1.0), 0.0);
  const Triangle<double> right{0.0, 1.0, 1.0};
  EXPECT_EQ(right(1.0), 1.0);
  EXPECT_EQ(right(std::nextafter(1.0, 2.0)), 0.0);
  EXPECT_EQ(right(0.75), 0.75);
  const Triangle<double> spike{1.0, 1.0, 1.0};
  EXPECT_EQ(spike(1.0), 1.0);
  EXPECT_EQ(spike(std::nextafter(1.0, 0.0)), 0.0);
  EXPECT_EQ(spike(std::nextafter(1.0, 2.0)), 0.0);
}

TEST(Trapezoid, MatchesItsClosedFormIncludingEdgesNaNAndInfinity) {
  const Trapezoid<double> t{-2.0, -1.0, 1.0, 3.0};
  const Case cases[] = {
      {-2.0, 0.0}, {-1.0, 1.0},  {0.0, 1.0},  {1.0, 1.0},  {3.0, 0.0},  {-1.5, 0.5},  {2.0, 0.5},
      {2.5, 0.25}, {-10.0, 0.0}, {10.0, 0.0}, {kNaN, 0.0}, {kInf, 0.0}, {-kInf, 0.0},
  };
  for (const auto& c : cases)
    EXPECT_NEAR(t(c.x), c.expected, 1e-15) << describe(c.x);
}

TEST(Trapezoid, InfiniteVerticesMakeOpenShouldersLikeFuzzylite) {
  const Trapezoid<double> nl{-kInf, -kInf, -0.3, -0.2};
  const Trapezoid<double> pl{0.2, 0.3, kInf, kInf};
  const Case nl_cases[] = {{-kInf, 1.0}, {-1e300, 1.0}, {-0.3, 1.0}, {-0.25, 0.5},
                           {-0.2, 0.0},  {0.0, 0.0},    {kInf, 0.0}, {kNaN, 0.0}};
  const Case pl_cases[] = {{kInf, 1.0}, {1e300, 1.0}, {0.3, 1.0},   {0.25, 0.5},
                           {0.2, 0.0},  {0.0, 0.0},   {-kInf, 0.0}, {kNaN, 0.0}};
  for (const auto& c : nl_cases)
    EXPECT_NEAR(nl(c.x), c.expected, 1e-15) << describe(c.x);
  for (const auto& c : pl_cases)
    EXPECT_NEAR(pl(c.x), c.expected, 1e-15) << describe(c.x);
  // Half-open: infinite left foot with a finite plateau start.
  const Trapezoid<double> ramp{-kInf, 0.0, 1.0, 2.0};
  EXPECT_EQ(ramp(-5.0), 1.0);
  EXPECT_EQ(ramp(1.5), 0.5);
}

TEST(Trapezoid, DegenerateVerticalEdgesAndTriangularPlateau) {
  const Trapezoid<double> box{0.0, 0.0, 1.0, 1.0};
  EXPECT_EQ(box(0.0), 1.0);
  EXPECT_EQ(box(1.0), 1.0);
  EXPECT_EQ(box(std::nextafter(0.0, -1.0)), 0.0);
  EXPECT_EQ(box(std::nextafter(1.0, 2.0)), 0.0);
  const Trapezoid<double> as_triangle{0.0, 1.0, 1.0, 2.0};
  const Triangle<double> triangle{0.0, 1.0, 2.0};
  for (double x : {-1.0, 0.0, 0.3, 1.0, 1.7, 2.0, 3.0})
    EXPECT_EQ(as_triangle(x), triangle(x));
}

TEST(Shoulders, MatchTheirClosedFormsIncludingNaNAndInfinity) {
  const LeftShoulder<double> left{-0.3, -0.2};
  const RightShoulder<double> right{0.2, 0.3};
  const Case left_cases[] = {{-kInf, 1.0}, {-7.0, 1.0}, {-0.3, 1.0}, {-0.25, 0.5},
                             {-0.2, 0.0},  {0.5, 0.0},  {kInf, 0.0}, {kNaN, 0.0}};
  const Case right_cases[] = {{kInf, 1.0}, {7.0, 1.0},  {0.3, 1.0},   {0.25, 0.5},
                              {0.2, 0.0},  {-0.5, 0.0}, {-kInf, 0.0}, {kNaN, 0.0}};
  for (const auto& c : left_cases)
    EXPECT_NEAR(left(c.x), c.expected, 1e-15) << describe(c.x);
  for (const auto& c : right_cases)
    EXPECT_NEAR(right(c.x), c.expected, 1e-15) << describe(c.x);
}

TEST(Shoulders, EqualTheInfiniteTrapezoidsOnRandomPoints) {
  const std::uint64_t seed = 12;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  fuzzypid::support::UniformReal<double> u(-1.0, 1.0);
  const LeftShoulder<double> left{-0.3, -0.2};
  const RightShoulder<double> right{0.2, 0.3};
  const Trapezoid<double> nl{-kInf, -kInf, -0.3, -0.2};
  const Trapezoid<double> pl{0.2, 0.3, kInf, kInf};
  for (int k = 0; k < 10000; ++k) {
    const double x = u(rng);
    ASSERT_EQ(left(x), nl(x)) << describe(x);
    ASSERT_EQ(right(x), pl(x)) << describe(x);
  }
}

TEST(Gaussian, EqualsStdExpOfItsFormula) {
  const std::uint64_t seed = 13;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  fuzzypid::support::UniformReal<double> u(-5.0, 5.0);
  fuzzypid::support::UniformReal<double> s(0.01, 3.0);
  for (int k = 0; k < 10000; ++k) {
    const Gaussian<double> g{u(rng), s(rng)};
    const double x = u(rng);
    const double closed = std::exp(-(x - g.mean) * (x - g.mean) / (2.0 * g.sigma * g.sigma));
    ASSERT_NEAR(g(x), closed, 1e-14) << describe(x);
  }
  const Gaussian<double> g{0.5, 0.2};
  EXPECT_EQ(g(0.5), 1.0);
  EXPECT_NEAR(g(0.7), std::exp(-0.5), 1e-15);
  EXPECT_EQ(g(kNaN), 0.0);
  EXPECT_EQ(g(kInf), 0.0);
  EXPECT_EQ(g(-kInf), 0.0);
}

TEST(Bell, EqualsStdPowOfItsFormula) {
  const std::uint64_t seed = 14;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  fuzzypid::support::UniformReal<double> u(-5.0, 5.0);
  fuzzypid::support::UniformReal<double> w(0.05, 3.0);
  fuzzypid::support::UniformReal<double> b(0.1, 5.0);
  for (int k = 0; k < 10000; ++k) {
    const Bell<double> bell{w(rng), b(rng), u(rng)};
    const double x = u(rng);
    const double closed =
        1.0 / (1.0 + std::pow(std::fabs((x - bell.center) / bell.width), 2.0 * bell.slope));
    ASSERT_NEAR(bell(x), closed, 1e-14) << describe(x);
  }
  const Bell<double> bell{2.0, 1.5, 1.0};
  EXPECT_EQ(bell(1.0), 1.0);
  EXPECT_NEAR(bell(3.0), 0.5, 1e-15);  // |x - c| = width gives 1/2 for every slope
  EXPECT_NEAR(bell(-1.0), 0.5, 1e-15);
  EXPECT_EQ(bell(kNaN), 0.0);
  EXPECT_EQ(bell(kInf), 0.0);
  EXPECT_EQ(bell(-kInf), 0.0);
  const Bell<double> negative_width{-2.0, 1.5, 1.0};  // |.| makes the sign of width irrelevant
  EXPECT_NEAR(negative_width(3.0), 0.5, 1e-15);
}

TEST(Singleton, IsOneOnlyAtItsPoint) {
  const Singleton<double> s{0.1};
  EXPECT_EQ(s(0.1), 1.0);
  EXPECT_EQ(s(std::nextafter(0.1, 1.0)), 0.0);
  EXPECT_EQ(s(kNaN), 0.0);
  EXPECT_EQ(s(kInf), 0.0);
}

TEST(Term, DispatchEqualsTheShapeStructs) {
  const std::uint64_t seed = 15;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  fuzzypid::support::UniformReal<double> u(-2.0, 2.0);
  fuzzypid::support::UniformReal<double> positive(0.05, 2.0);
  std::vector<double> xs = {kNaN, kInf, -kInf, 0.0};
  for (int k = 0; k < 2000; ++k)
    xs.push_back(u(rng));
  for (int k = 0; k < 200; ++k) {
    double p[4] = {u(rng), u(rng), u(rng), u(rng)};
    std::sort(p, p + 4);
    const double s1 = positive(rng);
    const double s2 = positive(rng);
    const auto tri = Term<double>::triangle(p[0], p[1], p[2]);
    const auto trap = Term<double>::trapezoid(p[0], p[1], p[2], p[3]);
    const auto ls = Term<double>::left_shoulder(p[0], p[1]);
    const auto rs = Term<double>::right_shoulder(p[0], p[1]);
    const auto gauss = Term<double>::gaussian(p[0], s1);
    const auto bell = Term<double>::bell(s1, s2, p[1]);
    const auto single = Term<double>::singleton(p[2]);
    EXPECT_EQ(tri.shape, Shape::Triangle);
    EXPECT_EQ(bell.shape, Shape::Bell);
    for (double x : xs) {
      ASSERT_EQ(tri(x), (Triangle<double>{p[0], p[1], p[2]}(x)));
      ASSERT_EQ(trap(x), (Trapezoid<double>{p[0], p[1], p[2], p[3]}(x)));
      ASSERT_EQ(ls(x), (LeftShoulder<double>{p[0], p[1]}(x)));
      ASSERT_EQ(rs(x), (RightShoulder<double>{p[0], p[1]}(x)));
      ASSERT_EQ(gauss(x), (Gaussian<double>{p[0], s1}(x)));
      ASSERT_EQ(bell(x), (Bell<double>{s1, s2, p[1]}(x)));
      ASSERT_EQ(single(x), (Singleton<double>{p[2]}(x)));
    }
  }
}

TEST(Term, CentersAreThePointsOfGreatestMembership) {
  EXPECT_EQ(Term<double>::triangle(-1.0, 0.25, 1.0).center(), 0.25);
  EXPECT_EQ(Term<double>::trapezoid(-1.0, 0.0, 0.5, 1.0).center(), 0.25);
  EXPECT_EQ(Term<double>::left_shoulder(-0.3, -0.2).center(), -0.3);
  EXPECT_EQ(Term<double>::right_shoulder(0.2, 0.3).center(), 0.3);
  EXPECT_EQ(Term<double>::gaussian(0.7, 0.1).center(), 0.7);
  EXPECT_EQ(Term<double>::bell(0.5, 2.0, -0.4).center(), -0.4);
  EXPECT_EQ(Term<double>::singleton(0.9).center(), 0.9);
  for (const auto& t :
       {Term<double>::triangle(-1.0, 0.25, 1.0), Term<double>::trapezoid(-1.0, 0.0, 0.5, 1.0),
        Term<double>::left_shoulder(-0.3, -0.2), Term<double>::right_shoulder(0.2, 0.3),
        Term<double>::gaussian(0.7, 0.1), Term<double>::bell(0.5, 2.0, -0.4),
        Term<double>::singleton(0.9)})
    EXPECT_EQ(t(t.center()), 1.0);
}

TEST(Term, ValidRejectsUnorderedNonFiniteAndDegenerateParameters) {
  EXPECT_TRUE(Term<double>::trapezoid(-kInf, -kInf, -0.3, -0.2).valid());
  EXPECT_TRUE(Term<double>::trapezoid(0.2, 0.3, kInf, kInf).valid());
  EXPECT_TRUE(Term<double>::triangle(0.0, 0.0, 1.0).valid());
  EXPECT_FALSE(Term<double>::triangle(0.0, 0.0, 0.0).valid());
  EXPECT_FALSE(Term<double>::triangle(kNaN, 0.0, 1.0).valid());
  EXPECT_FALSE(Term<double>::triangle(-kInf, 0.0, 1.0).valid());
  EXPECT_FALSE(Term<double>::trapezoid(0.0, 2.0, 1.0, 3.0).valid());
  EXPECT_FALSE(Term<double>::trapezoid(-kInf, -kInf, -kInf, 0.0).valid());
  EXPECT_FALSE(Term<double>::trapezoid(-kInf, -kInf, kInf, kInf).valid());
  EXPECT_FALSE(Term<double>::left_shoulder(1.0, 1.0).valid());
  EXPECT_FALSE(Term<double>::right_shoulder(1.0, 0.0).valid());
  EXPECT_FALSE(Term<double>::gaussian(0.0, 0.0).valid());
  EXPECT_FALSE(Term<double>::gaussian(0.0, -1.0).valid());
  EXPECT_FALSE(Term<double>::bell(0.0, 1.0, 0.0).valid());
  EXPECT_FALSE(Term<double>::bell(1.0, 0.0, 0.0).valid());
  EXPECT_FALSE(Term<double>::singleton(kNaN).valid());
}

struct TermCase {
  const char* what;
  Term<double> term;
  double x;
  double expected;
};

// fuzzylite 8's Arc (start end [height]): a quarter circle of radius r = end - start centered at
// end, h sqrt(r^2 - (x - end)^2) / |r| between start and end, h beyond end, 0 before start.
TEST(Arc, MatchesItsClosedFormIncludingBothDirectionsNaNAndInfinity) {
  const auto rising = Term<double>::make(Shape::Arc, 0.0, 2.0);
  const auto falling = Term<double>::make(Shape::Arc, 2.0, 0.0);
  const auto half = Term<double>::make(Shape::Arc, 0.0, 2.0, 0, 0, 0.5);
  const auto flat = Term<double>::make(Shape::Arc, 1.0, 1.0);
  const TermCase cases[] = {
      {"rising: 0 at start", rising, 0.0, 0.0},
      {"rising: sqrt(4 - 1) / 2", rising, 1.0, std::sqrt(3.0) / 2.0},
      {"rising: sqrt(4 - 1.6^2) / 2", rising, 0.4, 0.6},
      {"rising: 1 at end", rising, 2.0, 1.0},
      {"rising: 1 beyond end", rising, 3.0, 1.0},
      {"rising: 0 before start", rising, -1.0, 0.0},
      {"rising: +inf", rising, kInf, 1.0},
      {"rising: -inf", rising, -kInf, 0.0},
      {"rising: NaN", rising, kNaN, 0.0},
      {"falling: 0 at start", falling, 2.0, 0.0},
      {"falling: sqrt(4 - 1.6^2) / 2", falling, 1.6, 0.6},
      {"falling: 1 at end", falling, 0.0, 1.0},
      {"falling: 1 beyond end", falling, -1.0, 1.0},
      {"falling: 0 before start", falling, 3.0, 0.0},
      {"falling: -inf", falling, -kInf, 1.0},
      {"falling: +inf", falling, kInf, 0.0},
      {"falling: NaN", falling, kNaN, 0.0},
      {"height 0.5 scales", half, 1.0, 0.5 * std::sqrt(3.0) / 2.0},
      {"height 0.5 beyond end", half, kInf, 0.5},
      {"start = end: 0 there", flat, 1.0, 0.0},
      {"start = end: 0 beyond", flat, kInf, 0.0},
      {"start = end: 0 before", flat, -kInf, 0.0},
  };
  for (const TermCase& c : cases)
    EXPECT_NEAR(c.term(c.x), c.expected, 1e-15) << c.what << ", " << describe(c.x);
}

TEST(Arc, LiesOnItsCircleOnRandomPoints) {
  const std::uint64_t seed = 27;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  fuzzypid::support::UniformReal<double> u(-5.0, 5.0);
  fuzzypid::support::UniformReal<double> unit(0.0, 1.0);
  for (int k = 0; k < 10000; ++k) {
    const double s = u(rng), e = u(rng), h = 0.1 + 0.9 * unit(rng);
    const auto arc = Term<double>::make(Shape::Arc, s, e, 0, 0, h);
    ASSERT_TRUE(arc.valid());
    const double x = std::fmin(s, e) + std::fabs(e - s) * unit(rng);
    const double r = e - s;
    // (mu / h)^2 + ((x - end) / r)^2 = 1 on the arc
    ASSERT_NEAR(std::pow(arc(x) / h, 2) + std::pow((x - e) / r, 2), 1.0, 1e-9) << describe(x);
    ASSERT_EQ(arc(s), 0.0);
    ASSERT_EQ(arc(e), h);
  }
}

// fuzzylite 8 takes the arc on [start, c] with c = start + (end - start), which rounds to either
// side of end: between c and end it gives 0 (and at start, where r^2 - (x - c)^2 may round below
// 0, NaN). The arc reaches its height at end whatever the rounding.
TEST(Arc, ReachesItsHeightAtItsEndWhenStartPlusRadiusRoundsBelowIt) {
  const double s = -1.092, e = 4.431;
  ASSERT_LT(s + (e - s), e);  // c is an ulp below end
  const auto arc = Term<double>::make(Shape::Arc, s, e);
  EXPECT_EQ(arc(e), 1.0);  // fuzzylite 8: 0
  EXPECT_EQ(arc(s), 0.0);
  EXPECT_NEAR(arc(4.43), 0.9999999836084539, 1e-15);  // fuzzylite 8's value
}

// fuzzylite 8's SemiEllipse (start end [height]): the upper half of the ellipse over [s, e] with
// half-axes r = (e - s) / 2 and h, centered at c = s + r; start and end in either order.
TEST(SemiEllipse, MatchesItsClosedFormIncludingNaNAndInfinity) {
  const auto se = Term<double>::make(Shape::SemiEllipse, 1.0, 5.0);
  const auto reversed = Term<double>::make(Shape::SemiEllipse, 5.0, 1.0);
  const auto low = Term<double>::make(Shape::SemiEllipse, 1.0, 5.0, 0, 0, 0.25);
  const TermCase cases[] = {
      {"1 at the center", se, 3.0, 1.0},
      {"0 at start", se, 1.0, 0.0},
      {"0 at end", se, 5.0, 0.0},
      {"sqrt(4 - 1) / 2", se, 2.0, std::sqrt(3.0) / 2.0},
      {"sqrt(4 - 1.2^2) / 2", se, 4.2, 0.8},
      {"0 before", se, 0.0, 0.0},
      {"0 after", se, 6.0, 0.0},
      {"+inf", se, kInf, 0.0},
      {"-inf", se, -kInf, 0.0},
      {"NaN", se, kNaN, 0.0},
      {"reversed: same set", reversed, 4.2, 0.8},
      {"reversed: +inf", reversed, kInf, 0.0},
      {"height 0.25 at the center", low, 3.0, 0.25},
      {"height 0.25 scales", low, 2.0, 0.25 * std::sqrt(3.0) / 2.0},
  };
  for (const TermCase& c : cases)
    EXPECT_NEAR(c.term(c.x), c.expected, 1e-15) << c.what << ", " << describe(c.x);
}

// fuzzylite 8 gives NaN at an end of 8 % of random semi-ellipses, where r^2 - (x - c)^2 rounds
// below 0; the set is 0 there. Elsewhere the rounding of c leaves at most sqrt(2 r ulp(c)) / r at
// an end, as in fuzzylite 8.
TEST(SemiEllipse, IsNeverNaNAtItsEndsWhereTheSquareRootsArgumentRoundsBelowZero) {
  const double s = -5.67, e = -1.56;
  const double r = (e - s) / 2, c = s + r;
  ASSERT_LT(r * r - (e - c) * (e - c), 0.0);  // the case
  const auto se = Term<double>::make(Shape::SemiEllipse, s, e);
  EXPECT_EQ(se(e), 0.0);  // fuzzylite 8: NaN
  EXPECT_EQ(se(s), 0.0);
  const std::uint64_t seed = 28;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  fuzzypid::support::UniformReal<double> u(-10.0, 10.0);
  for (int k = 0; k < 10000; ++k) {
    const double a = u(rng), b = u(rng);
    const auto t = Term<double>::make(Shape::SemiEllipse, a, b);
    const double x = std::fmin(a, b) + std::fabs(b - a) * (u(rng) + 10.0) / 20.0;
    const double half = std::fabs(b - a) / 2, center = std::fmin(a, b) + half;
    // 0 up to the rounding of c (an ulp of the larger end), never NaN
    const double ulp =
        std::numeric_limits<double>::epsilon() * std::fmax(std::fabs(a), std::fabs(b));
    const double bound = 2.0 * std::sqrt(2.0 * half * ulp) / half;
    ASSERT_LE(t(a), bound) << a << " " << b;
    ASSERT_LE(t(b), bound) << a << " " << b;
    ASSERT_NEAR(std::pow(t(x), 2) + std::pow((x - center) / half, 2), 1.0, 1e-9);
  }
}

TEST(Term, ArcAndSemiEllipseCentersAndValidity) {
  EXPECT_EQ(Term<double>::make(Shape::Arc, 0.0, 2.0).center(), 2.0);
  EXPECT_EQ(Term<double>::make(Shape::Arc, 2.0, 0.0).center(), 0.0);
  EXPECT_EQ(Term<double>::make(Shape::SemiEllipse, 1.0, 5.0).center(), 3.0);
  EXPECT_TRUE(Term<double>::make(Shape::Arc, 1.0, 1.0).valid());  // 0 everywhere, as fuzzylite 8
  EXPECT_FALSE(Term<double>::make(Shape::Arc, 0.0, kInf).valid());
  EXPECT_FALSE(Term<double>::make(Shape::Arc, kNaN, 1.0).valid());
  EXPECT_FALSE(Term<double>::make(Shape::SemiEllipse, 1.0, 1.0).valid());  // 0 / 0
  EXPECT_FALSE(Term<double>::make(Shape::SemiEllipse, -kInf, 1.0).valid());
  EXPECT_FALSE(Term<double>::make(Shape::SemiEllipse, 0.0, 1.0, 0, 0, -0.5).valid());
}

// The paper's seven input sets, each evaluated through its own Term.
std::array<double, 7> paper_degrees(double x) {
  const auto v = fuzzypid::paper::make_system<double>().e;
  std::array<double, 7> d{};
  for (std::size_t k = 0; k < 7; ++k)
    d[k] = v.term(k)(x);
  return d;
}

TEST(PaperPartition, DegreesSumToOneInsideTheUniverse) {
  const std::uint64_t seed = 16;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  fuzzypid::support::UniformReal<double> u(-0.3, 0.3);
  const auto v = fuzzypid::paper::make_system<double>().e;
  std::vector<double> xs = {-0.3, -0.2, -0.1, 0.0, 0.1, 0.2, 0.3};
  for (int k = 0; k < 100000; ++k)
    xs.push_back(u(rng));
  for (double x : xs) {
    double sum_terms = 0.0;
    int nonzero = 0;
    for (double d : paper_degrees(x)) {
      ASSERT_GE(d, 0.0);
      ASSERT_LE(d, 1.0);
      sum_terms += d;
      nonzero += d > 0.0;
    }
    ASSERT_NEAR(sum_terms, 1.0, 1e-15) << describe(x);
    ASSERT_LE(nonzero, 2) << describe(x);
    double sum_fuzzified = 0.0;
    for (double d : v.fuzzify(x).degree)
      sum_fuzzified += d;
    ASSERT_NEAR(sum_fuzzified, 1.0, 1e-15) << describe(x);
  }
}

TEST(PaperPartition, OutsideTheUniverseTheOuterSetsSaturate) {
  const auto v = fuzzypid::paper::make_system<double>().e;
  for (double x : {-0.3, -0.30000001, -1.0, -1e300, -std::numeric_limits<double>::max()}) {
    const auto d = paper_degrees(x);
    const auto f = v.fuzzify(x);
    EXPECT_EQ(d[0], 1.0) << describe(x);
    EXPECT_EQ(f.degree[0], 1.0) << describe(x);
    EXPECT_EQ(f.first, 0u);
    EXPECT_EQ(f.last, 0u);
    for (std::size_t k = 1; k < 7; ++k) {
      EXPECT_EQ(d[k], 0.0) << describe(x);
      EXPECT_EQ(f.degree[k], 0.0) << describe(x);
    }
  }
  for (double x : {0.3, 0.30000001, 1.0, 1e300, std::numeric_limits<double>::max()}) {
    const auto d = paper_degrees(x);
    const auto f = v.fuzzify(x);
    EXPECT_EQ(d[6], 1.0) << describe(x);
    EXPECT_EQ(f.degree[6], 1.0) << describe(x);
    EXPECT_EQ(f.first, 6u);
    EXPECT_EQ(f.last, 6u);
    for (std::size_t k = 0; k < 6; ++k) {
      EXPECT_EQ(d[k], 0.0) << describe(x);
      EXPECT_EQ(f.degree[k], 0.0) << describe(x);
    }
  }
}

TEST(PaperPartition, HasTheTermsOfFigure4) {
  const auto v = fuzzypid::paper::make_system<double>().e;
  EXPECT_TRUE(v.is_uniform());
  EXPECT_EQ(v.min(), -0.3);
  EXPECT_EQ(v.max(), 0.3);
  EXPECT_EQ(v.term(0).shape, Shape::LeftShoulder);
  EXPECT_EQ(v.term(6).shape, Shape::RightShoulder);
  for (std::size_t k = 1; k < 6; ++k)
    EXPECT_EQ(v.term(k).shape, Shape::Triangle);
  const double peaks[7] = {-0.3, -0.2, -0.1, 0.0, 0.1, 0.2, 0.3};
  for (std::size_t k = 0; k < 7; ++k)
    EXPECT_NEAR(v.centers()[k], peaks[k], 2e-16);
}

TEST(LinguisticVariable, NaNBelongsToNoTerm) {
  const auto v = LinguisticVariable<double, 7>::uniform(-0.3, 0.3);
  const auto f = v.fuzzify(kNaN);
  EXPECT_TRUE(f.empty());
  for (double d : f.degree)
    EXPECT_EQ(d, 0.0);
  const auto c = LinguisticVariable<double, 7>::custom(-0.3, 0.3, v.terms());
  EXPECT_TRUE(c.fuzzify(kNaN).empty());
}

TEST(LinguisticVariable, InfinitySaturatesAtTheOuterTerm) {
  const auto v = LinguisticVariable<double, 7>::uniform(-0.3, 0.3);
  EXPECT_EQ(v.fuzzify(kInf).degree[6], 1.0);
  EXPECT_EQ(v.fuzzify(-kInf).degree[0], 1.0);
}

// Compares the O(1) uniform path with a custom variable holding the same terms (which evaluates
// every term): the degrees are equal up to rounding -- the uniform path reads them off the
// position t = (x - min) / h, computed with the precomputed 1/h, so they may differ by a few ulp
// of t -- and a term that holds x on one side only holds it with such a rounding-sized degree.
template <class Scalar, std::size_t N>
void expect_uniform_fast_path_equals_every_term(Scalar min, Scalar max, std::uint64_t seed) {
  SCOPED_TRACE("N = " + std::to_string(N) + ", seed " + std::to_string(seed));
  const auto uniform = LinguisticVariable<Scalar, N>::uniform(min, max);
  const auto every = LinguisticVariable<Scalar, N>::custom(min, max, uniform.terms());
  ASSERT_TRUE(uniform.is_uniform());
  ASSERT_FALSE(every.is_uniform());
  std::mt19937_64 rng(seed);
  const Scalar span = max - min;
  fuzzypid::support::UniformReal<Scalar> u(min - span / 4, max + span / 4);
  std::vector<Scalar> xs(uniform.centers().begin(), uniform.centers().end());
  for (Scalar c : uniform.centers()) {
    xs.push_back(std::nextafter(c, min - span));
    xs.push_back(std::nextafter(c, max + span));
  }
  for (int k = 0; k < 20000; ++k)
    xs.push_back(u(rng));
  for (Scalar x : xs) {
    const auto fast = uniform.fuzzify(x);
    const auto slow = every.fuzzify(x);
    const Scalar rounding = Scalar(4 * N) * std::numeric_limits<Scalar>::epsilon();
    for (std::size_t k = 0; k < N; ++k) {
      ASSERT_NEAR(fast.degree[k], slow.degree[k], rounding) << "term " << k << " at x = " << x;
      const bool in_fast = k >= fast.first && k <= fast.last;
      const bool in_slow = k >= slow.first && k <= slow.last;
      if (in_fast != in_slow) {
        ASSERT_LE(fast.degree[k] + slow.degree[k], rounding) << "term " << k << " at x = " << x;
      }
    }
  }
}

TEST(LinguisticVariable, UniformFastPathEqualsEvaluatingEveryTerm) {
  expect_uniform_fast_path_equals_every_term<double, 7>(-0.3, 0.3, 21);
  expect_uniform_fast_path_equals_every_term<double, 2>(-1.0, 1.0, 22);
  expect_uniform_fast_path_equals_every_term<double, 5>(0.0, 3.0, 23);
  expect_uniform_fast_path_equals_every_term<double, 11>(-7.3, 2.9, 24);
  expect_uniform_fast_path_equals_every_term<float, 7>(-0.3f, 0.3f, 25);
}

TEST(LinguisticVariable, CustomVariableWithAGapHasNoTermThere) {
  const std::array<Term<double>, 2> terms{Term<double>::triangle(0.0, 1.0, 2.0),
                                          Term<double>::triangle(3.0, 4.0, 5.0)};
  const auto v = LinguisticVariable<double, 2>::custom(0.0, 5.0, terms);
  EXPECT_TRUE(v.valid());
  EXPECT_EQ(v.centers()[1], 4.0);
  EXPECT_TRUE(v.fuzzify(2.5).empty());
  const auto f = v.fuzzify(1.5);
  EXPECT_EQ(f.first, 0u);
  EXPECT_EQ(f.last, 0u);
  EXPECT_EQ(f.degree[0], 0.5);
}

TEST(LinguisticVariable, ValidRejectsBadUniversesAndTerms) {
  const auto good = LinguisticVariable<double, 7>::uniform(-0.3, 0.3);
  EXPECT_FALSE((LinguisticVariable<double, 7>::uniform(0.3, 0.3).valid()));
  EXPECT_FALSE((LinguisticVariable<double, 7>::uniform(-kInf, 0.3).valid()));
  EXPECT_FALSE((LinguisticVariable<double, 7>::uniform(kNaN, 0.3).valid()));
  auto terms = good.terms();
  terms[3] = Term<double>::gaussian(0.0, -1.0);
  EXPECT_FALSE((LinguisticVariable<double, 7>::custom(-0.3, 0.3, terms).valid()));
}

// An open right side (c = +inf) is a shoulder: 1 from the peak on, up to +inf itself.
TEST(Triangle, AnOpenRightSideHoldsOneBeyondThePeak) {
  const Triangle<double> t{0.0, 1.0, kInf};
  EXPECT_EQ(t(0.5), 0.5);
  EXPECT_EQ(t(2.0), 1.0);
  EXPECT_EQ(t(1e300), 1.0);
  EXPECT_EQ(t(kInf), 1.0);
  const Triangle<double> left{-kInf, -1.0, 0.0};
  EXPECT_EQ(left(-1e300), 1.0);
  EXPECT_EQ(left(-0.5), 0.5);
}

// --- Formulas (Function terms): compiled postfix programs --------------------------------------

using fuzzypid::fuzzy::evaluate_formula;
using fuzzypid::fuzzy::formula_depth;
using fuzzypid::fuzzy::FormulaOp;
using Step = fuzzypid::fuzzy::FormulaStep<double>;

Step num(double v) {
  return {FormulaOp::Number, 0, v};
}
Step op(FormulaOp o, std::uint8_t input = 0) {
  return {o, input, 0.0};
}

double run(const std::vector<Step>& steps, double x = 0.0, const double* inputs = nullptr) {
  EXPECT_GT(formula_depth(steps.data(), steps.size(), 2, true), 0u);
  return evaluate_formula(steps.data(), steps.size(), x, inputs);
}

// splitmix64: a generator whose sequence is the same on every platform.
struct SplitMix {
  std::uint64_t s;
  double uniform(double lo, double hi) {
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return lo + (hi - lo) * static_cast<double>(z >> 11) * 0x1.0p-53;
  }
};

TEST(Formula, EvaluatesPostfixStepsAsTheirClosedForm) {
  // (x + 2 in0) ^ 2 / (1 + |in1|) - sin(x) * atan2(in0, in1) + fmod(x, 0.7)
  const std::vector<Step> f = {op(FormulaOp::X),
                               num(2),
                               op(FormulaOp::Input, 0),
                               op(FormulaOp::Multiply),
                               op(FormulaOp::Add),
                               num(2),
                               op(FormulaOp::Power),
                               num(1),
                               op(FormulaOp::Input, 1),
                               op(FormulaOp::Abs),
                               op(FormulaOp::Add),
                               op(FormulaOp::Divide),
                               op(FormulaOp::X),
                               op(FormulaOp::Sin),
                               op(FormulaOp::Input, 0),
                               op(FormulaOp::Input, 1),
                               op(FormulaOp::Atan2),
                               op(FormulaOp::Multiply),
                               op(FormulaOp::Subtract),
                               op(FormulaOp::X),
                               num(0.7),
                               op(FormulaOp::Fmod),
                               op(FormulaOp::Add)};
  ASSERT_EQ(formula_depth(f.data(), f.size(), 2, true), 4u);
  const std::uint64_t seed = 20240527;
  SplitMix rng{seed};
  for (int n = 0; n < 100000; ++n) {
    const double x = rng.uniform(-50, 50);
    const double in[2] = {rng.uniform(-10, 10), rng.uniform(-10, 10)};
    const double expected = std::pow(x + 2 * in[0], 2.0) / (1 + std::fabs(in[1])) -
                            std::sin(x) * std::atan2(in[0], in[1]) + std::fmod(x, 0.7);
    ASSERT_DOUBLE_EQ(evaluate_formula(f.data(), f.size(), x, in), expected)
        << "seed " << seed << ", sample " << n << ", x = " << x;
  }
}

// numpy's meanings (fuzzylite 8), where C's differ: %, round, the comparisons, NaN as true.
TEST(Formula, OperationsMeanWhatNumpyComputes) {
  const auto bin = [](FormulaOp o, double a, double b) { return run({num(a), num(b), op(o)}); };
  const auto un = [](FormulaOp o, double a) { return run({num(a), op(o)}); };
  EXPECT_EQ(bin(FormulaOp::Modulo, -7, 3), 2.0);  // the sign of the divisor
  EXPECT_EQ(bin(FormulaOp::Modulo, 7, -3), -2.0);
  EXPECT_EQ(bin(FormulaOp::Modulo, 5.5, 2), 1.5);
  EXPECT_TRUE(std::signbit(bin(FormulaOp::Modulo, 6, -3)));  // -0.0
  EXPECT_TRUE(std::isnan(bin(FormulaOp::Modulo, 1, 0)));
  EXPECT_EQ(bin(FormulaOp::Fmod, -7, 3), -1.0);  // the sign of the dividend
  EXPECT_EQ(un(FormulaOp::Round, 2.5), 2.0);     // ties to even
  EXPECT_EQ(un(FormulaOp::Round, 3.5), 4.0);
  EXPECT_EQ(un(FormulaOp::Round, -2.5), -2.0);
  EXPECT_EQ(un(FormulaOp::Round, 2.4999999999999996), 2.0);
  EXPECT_EQ(un(FormulaOp::Round, -2.6), -3.0);
  EXPECT_TRUE(std::signbit(un(FormulaOp::Round, -0.4)));
  EXPECT_EQ(un(FormulaOp::Round, 1e300), 1e300);
  EXPECT_EQ(bin(FormulaOp::Power, 2, 10), 1024.0);
  EXPECT_EQ(bin(FormulaOp::Eq, kNaN, kNaN), 1.0);  // NaN equals NaN, as np.isclose(equal_nan)
  EXPECT_EQ(bin(FormulaOp::Neq, kNaN, kNaN), 0.0);
  EXPECT_EQ(bin(FormulaOp::Ge, kNaN, kNaN), 1.0);
  EXPECT_EQ(bin(FormulaOp::Le, kNaN, 1), 0.0);
  EXPECT_EQ(bin(FormulaOp::Gt, kNaN, 0), 0.0);
  EXPECT_EQ(bin(FormulaOp::Lt, -kInf, 0), 1.0);
  EXPECT_EQ(bin(FormulaOp::Ge, 2, 1), 1.0);
  EXPECT_EQ(bin(FormulaOp::Le, 2, 1), 0.0);
  EXPECT_EQ(un(FormulaOp::Not, 0), 1.0);
  EXPECT_EQ(un(FormulaOp::Not, kNaN), 0.0);  // NaN is true
  EXPECT_EQ(bin(FormulaOp::And, kNaN, 2), 1.0);
  EXPECT_EQ(bin(FormulaOp::And, 0, 2), 0.0);
  EXPECT_EQ(bin(FormulaOp::Or, 0, 0), 0.0);
  EXPECT_EQ(bin(FormulaOp::Or, 0, -1), 1.0);
  EXPECT_TRUE(std::isnan(bin(FormulaOp::Min, kNaN, 1)));  // Python's min(a, b): b < a ? b : a
  EXPECT_EQ(bin(FormulaOp::Min, 1, kNaN), 1.0);
  EXPECT_EQ(bin(FormulaOp::Max, 1, 2), 2.0);
  EXPECT_EQ(un(FormulaOp::Negate, 3), -3.0);
  EXPECT_EQ(un(FormulaOp::Plus, -3), -3.0);
  EXPECT_EQ(run({op(FormulaOp::Pi)}), 3.141592653589793);
}

TEST(Formula, DomainErrorsGiveTheirIeeeValues) {
  EXPECT_TRUE(std::isnan(run({num(-1), op(FormulaOp::Sqrt)})));
  EXPECT_TRUE(std::isnan(run({num(2), op(FormulaOp::Acos)})));
  EXPECT_EQ(run({num(0), op(FormulaOp::Log)}), -kInf);
  EXPECT_EQ(run({num(1), num(0), op(FormulaOp::Divide)}), kInf);
  EXPECT_TRUE(std::isnan(run({num(-8), num(1.0 / 3), op(FormulaOp::Power)})));
  EXPECT_EQ(run({num(1), op(FormulaOp::Atanh)}), kInf);
}

TEST(Formula, DepthRefusesMalformedProgramsAndDeepStacks) {
  const auto depth = [](const std::vector<Step>& s, bool x_allowed = true) {
    return formula_depth(s.data(), s.size(), 2, x_allowed);
  };
  EXPECT_EQ(depth({}), 0u);
  EXPECT_EQ(depth({num(1), op(FormulaOp::Add)}), 0u);       // an operand missing
  EXPECT_EQ(depth({num(1), num(2)}), 0u);                   // two values left
  EXPECT_EQ(depth({op(FormulaOp::Input, 2)}), 0u);          // no third input
  EXPECT_EQ(depth({op(FormulaOp::X)}, false), 0u);          // x where not allowed
  EXPECT_EQ(depth({op(static_cast<FormulaOp>(200))}), 0u);  // no such operation
  EXPECT_EQ(depth({num(1), op(FormulaOp::Negate)}), 1u);
  std::vector<Step> deep;
  for (std::size_t k = 0; k < fuzzypid::fuzzy::kMaxFormulaDepth; ++k)
    deep.push_back(num(1));
  for (std::size_t k = 1; k < fuzzypid::fuzzy::kMaxFormulaDepth; ++k)
    deep.push_back(op(FormulaOp::Add));
  EXPECT_EQ(depth(deep), fuzzypid::fuzzy::kMaxFormulaDepth);
  EXPECT_EQ(run(deep), static_cast<double>(fuzzypid::fuzzy::kMaxFormulaDepth));
  deep.insert(deep.begin(), num(1));
  deep.push_back(op(FormulaOp::Add));
  EXPECT_EQ(depth(deep), 0u);  // one value deeper than the evaluation's stack
}

// A Function term alone has no formula to read (the engine evaluates it with the model's pool).
TEST(Formula, AFunctionTermIsValidWithStepsAndZeroAlone) {
  Term<double> t{};
  t.shape = Shape::Function;
  EXPECT_FALSE(t.valid());
  t.count = 3;
  EXPECT_TRUE(t.valid());
  EXPECT_EQ(t(0.5), 0.0);
}

}  // namespace
