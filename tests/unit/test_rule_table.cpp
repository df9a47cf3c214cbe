// supervisor::RuleTable, the supervisor of the fuzzy-rules family: a zero-order Sugeno rule base
// (product AND, weighted average over a strong partition) refining GainSchedule's ramp.
//
// The closed forms it is held to:
//   rho_g(x, y)   = sum_ij mu_i(x) nu_j(y) T_g[i][j] / sum_ij mu_i(x) nu_j(y), evaluated here over
//                   all Sets x Sets rules with triangles written out independently of the header;
//   ratio_g       = (1 + (R_g - 1) min(1, |x| + |y|)) rho_g,  delta_g = ratio_g - 1;
//   a bilinear function tabulated on the nodes is reproduced everywhere inside c_max;
//   T = 1 reproduces GainSchedule: delta = (R - 1) w bit for bit, and FuzzyPid with S = K0 gives
//   the commands of FuzzyPid<GainSchedule> with S = K0 (R - 1) to a few ulp.
//
// This executable replaces global operator new (fuzzypid_support/counting_new.hpp) to prove that
// infer() allocates nothing.
// First, on purpose: rule_table.hpp must not hide fuzzypid::detail from the headers after it.
#include "fuzzypid/supervisor/rule_table.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <utility>

#include "fuzzypid/supervisor/fuzzy_pid.hpp"
#include "fuzzypid/supervisor/gain_schedule.hpp"
#include "fuzzypid/supervisor/supervisor.hpp"
#include "fuzzypid_support/counting_new.hpp"
#include "fuzzypid_support/uniform_real.hpp"

namespace {

using fuzzypid::Status;
using fuzzypid::supervisor::FuzzyPid;
using fuzzypid::supervisor::FuzzyPidConfig;
using fuzzypid::supervisor::GainSchedule;
using fuzzypid::supervisor::RuleTable;
using fuzzypid::support::allocation_count;

static_assert(fuzzypid::supervisor::is_supervisor_v<RuleTable<double>, double>);
static_assert(fuzzypid::supervisor::is_supervisor_v<RuleTable<float, 5>, float>);

// Constexpr data, as a generated header for a microcontroller would hold it.
constexpr RuleTable<double> kDefault{};
static_assert(kDefault.valid());
static_assert(kDefault.e_centers[0] == -1.0 && kDefault.e_centers[3] == 0.0 &&
              kDefault.e_centers[6] == 1.0);
static_assert(kDefault.ratio(0.2, -0.3, 0) == 1.0);
constexpr RuleTable<float, 5> kSmall{{2.0f, 0.5f, 1.0f}};
static_assert(kSmall.valid() && kSmall.ratio(4.0f, 0.0f, 0) == 2.0f);

template <class Scalar, std::size_t Sets>
std::string describe(const RuleTable<Scalar, Sets>& m) {
  std::string s = "R = (" + std::to_string(m.schedule_ratio[0]) + ", " +
                  std::to_string(m.schedule_ratio[1]) + ", " + std::to_string(m.schedule_ratio[2]) +
                  "), e centers";
  for (Scalar c : m.e_centers)
    s += " " + std::to_string(c);
  s += ", ec centers";
  for (Scalar c : m.ec_centers)
    s += " " + std::to_string(c);
  return s;
}

template <class Scalar>
Scalar uniform(std::mt19937_64& rng, double lo, double hi) {
  return static_cast<Scalar>(fuzzypid::support::UniformReal<double>(lo, hi)(rng));
}

// Random symmetric ascending centers with c_max in [0.5, 2].
template <class Scalar, std::size_t Sets>
std::array<Scalar, Sets> random_centers(std::mt19937_64& rng) {
  constexpr std::size_t m = (Sets - 1) / 2;
  std::array<Scalar, Sets> c{};
  double v = 0.0;
  for (std::size_t k = m + 1; k < Sets; ++k) {
    v += fuzzypid::support::UniformReal<double>(0.1, 0.7)(rng);
    c[k] = static_cast<Scalar>(v);
    c[Sets - 1 - k] = -c[k];
  }
  return c;
}

// A random valid model: T in [0.5, 2], R in [0.3, 3], random centers.
template <class Scalar, std::size_t Sets>
RuleTable<Scalar, Sets> random_model(std::mt19937_64& rng) {
  RuleTable<Scalar, Sets> m;
  for (auto& r : m.schedule_ratio)
    r = uniform<Scalar>(rng, 0.3, 3.0);
  for (auto& t : m.table)
    for (auto& row : t)
      for (auto& v : row)
        v = uniform<Scalar>(rng, 0.5, 2.0);
  m.e_centers = random_centers<Scalar, Sets>(rng);
  m.ec_centers = random_centers<Scalar, Sets>(rng);
  return m;
}

// Degree of x in set k of a partition with centers c (the definition, written out in long
// double): triangles with feet at the neighbouring centers, shoulders at the ends.
template <class Scalar, std::size_t Sets>
long double membership(const std::array<Scalar, Sets>& c, std::size_t k, long double x) {
  const long double ck = c[k];
  if (k == 0 && x <= ck) return 1.0L;
  if (k + 1 == Sets && x >= ck) return 1.0L;
  if (k > 0 && x > c[k - 1] && x <= ck) return (x - c[k - 1]) / (ck - c[k - 1]);
  if (k + 1 < Sets && x >= ck && x < c[k + 1]) return (c[k + 1] - x) / (c[k + 1] - ck);
  return 0.0L;
}

// rho_g over all Sets x Sets rules: sum mu nu T / sum mu nu.
template <class Scalar, std::size_t Sets>
long double weighted_average(const RuleTable<Scalar, Sets>& m, Scalar x, Scalar y, std::size_t g) {
  long double num = 0.0L, den = 0.0L;
  for (std::size_t i = 0; i < Sets; ++i)
    for (std::size_t j = 0; j < Sets; ++j) {
      const long double w = membership(m.e_centers, i, x) * membership(m.ec_centers, j, y);
      num += w * m.table[g][i][j];
      den += w;
    }
  return num / den;
}

template <class Scalar>
constexpr double tolerance() {
  return std::is_same_v<Scalar, float> ? 2e-6 : 4e-15;
}

template <class Scalar>
class RuleTableTyped : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(RuleTableTyped, Scalars);

TYPED_TEST(RuleTableTyped, RatioIsTheWeightedAverageOfAllRulesTimesTheScheduleRamp) {
  using Scalar = TypeParam;
  const std::uint64_t seed = 0x7ab1e5eedULL;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  double worst = 0.0;
  for (int n = 0; n < 200; ++n) {
    const auto m = random_model<Scalar, 7>(rng);
    ASSERT_TRUE(m.valid()) << describe(m);
    auto ws = m.make_workspace();
    for (int k = 0; k < 200; ++k) {
      // Inside and well outside the universe (saturation).
      const Scalar x = uniform<Scalar>(rng, -3.0, 3.0);
      const Scalar y = uniform<Scalar>(rng, -3.0, 3.0);
      std::array<Scalar, 3> delta{};
      ASSERT_EQ(m.infer(x, y, ws, delta), Status::Ok);
      const long double w = std::min(1.0L, std::fabs((long double)x) + std::fabs((long double)y));
      for (std::size_t g = 0; g < 3; ++g) {
        const long double rho = weighted_average(m, x, y, g);
        const long double ratio = (1.0L + (m.schedule_ratio[g] - 1.0L) * w) * rho;
        const double err = static_cast<double>(std::fabs(delta[g] - (ratio - 1.0L)));
        worst = std::max(worst, err);
        ASSERT_LE(err, tolerance<Scalar>() * 10) << describe(m) << " x=" << x << " y=" << y;
        ASSERT_EQ(m.ratio(x, y, g), Scalar(1) + delta[g]);
        ASSERT_LE(std::fabs(m.refinement(x, y, g) - rho), tolerance<Scalar>() * 4);
      }
    }
  }
  std::printf("largest |delta - closed form|: %.3g\n", worst);
}

TYPED_TEST(RuleTableTyped, ReproducesABilinearFunctionTabulatedOnTheNodes) {
  // T[i][j] = f(c_i, d_j) with f = a + b x + c y + d x y: bilinear interpolation returns f
  // everywhere inside the universe and f(clamped x, clamped y) outside; nodes exactly.
  using Scalar = TypeParam;
  const std::uint64_t seed = 0xb111ea5ULL;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  double worst = 0.0;
  for (int n = 0; n < 200; ++n) {
    RuleTable<Scalar, 9> m;
    m.e_centers = random_centers<Scalar, 9>(rng);
    m.ec_centers = random_centers<Scalar, 9>(rng);
    const double a = uniform<double>(rng, 20.0, 30.0), b = uniform<double>(rng, -1.0, 1.0),
                 c = uniform<double>(rng, -1.0, 1.0), d = uniform<double>(rng, -1.0, 1.0);
    const auto f = [&](long double x, long double y) { return a + b * x + c * y + d * x * y; };
    for (std::size_t i = 0; i < 9; ++i)
      for (std::size_t j = 0; j < 9; ++j)
        m.table[0][i][j] = static_cast<Scalar>(f(m.e_centers[i], m.ec_centers[j]));
    ASSERT_TRUE(m.valid());
    for (std::size_t i = 0; i < 9; ++i)
      for (std::size_t j = 0; j < 9; ++j)
        ASSERT_EQ(m.refinement(m.e_centers[i], m.ec_centers[j], 0), m.table[0][i][j])
            << "node " << i << ", " << j;
    const long double xm = m.e_centers[8], ym = m.ec_centers[8];
    for (int k = 0; k < 500; ++k) {
      const Scalar x = uniform<Scalar>(rng, -3.0, 3.0);
      const Scalar y = uniform<Scalar>(rng, -3.0, 3.0);
      const long double xc = std::clamp<long double>(x, -xm, xm);
      const long double yc = std::clamp<long double>(y, -ym, ym);
      // Centers up to 2.8 in magnitude: 0 < f <= 44. Tabulating in Scalar already rounds T.
      const double err = static_cast<double>(std::fabs(m.refinement(x, y, 0) - f(xc, yc)));
      worst = std::max(worst, err);
      ASSERT_LE(err, 44 * tolerance<Scalar>()) << describe(m) << " x=" << x << " y=" << y;
    }
  }
  std::printf("largest |rho - f|: %.3g\n", worst);
}

TYPED_TEST(RuleTableTyped, UnitTableGivesTheScheduleRampBitForBit) {
  // With T = 1, rho is exactly 1 and delta_g = (R_g - 1) w, w being GainSchedule's own output.
  using Scalar = TypeParam;
  const std::uint64_t seed = 0x0e1ULL;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  const GainSchedule<Scalar> schedule;
  auto sws = schedule.make_workspace();
  for (int n = 0; n < 100; ++n) {
    RuleTable<Scalar> m;
    for (auto& r : m.schedule_ratio)
      r = uniform<Scalar>(rng, 0.2, 4.0);
    m.e_centers = random_centers<Scalar, 7>(rng);
    m.ec_centers = random_centers<Scalar, 7>(rng);
    auto ws = m.make_workspace();
    for (int k = 0; k < 1000; ++k) {
      const Scalar x = uniform<Scalar>(rng, -2.0, 2.0);
      const Scalar y = uniform<Scalar>(rng, -2.0, 2.0);
      std::array<Scalar, 3> delta{}, w{};
      ASSERT_EQ(m.infer(x, y, ws, delta), Status::Ok);
      ASSERT_EQ(schedule.infer(x, y, sws, w), Status::Ok);
      for (std::size_t g = 0; g < 3; ++g) {
        ASSERT_EQ(m.refinement(x, y, g), Scalar(1)) << "x=" << x << " y=" << y;
        ASSERT_EQ(delta[g], (m.schedule_ratio[g] - Scalar(1)) * w[g]) << "x=" << x << " y=" << y;
      }
    }
  }
}

TYPED_TEST(RuleTableTyped, ShouldersSaturateBeyondTheOutermostCenters) {
  using Scalar = TypeParam;
  std::mt19937_64 rng(0x5a7ULL);
  const auto m = random_model<Scalar, 7>(rng);
  const Scalar xm = m.e_centers[6], ym = m.ec_centers[6];
  const Scalar big = std::numeric_limits<Scalar>::max();
  for (const Scalar y : {Scalar(-0.3), Scalar(0), Scalar(0.1)}) {
    for (const Scalar x : {xm, Scalar(1.5) * xm, Scalar(1e6), big}) {
      EXPECT_EQ(m.refinement(x, y, 1), m.refinement(xm, y, 1)) << "x=" << x;
      EXPECT_EQ(m.refinement(-x, y, 1), m.refinement(-xm, y, 1)) << "x=" << -x;
    }
  }
  // A corner beyond both maxima fires exactly one rule, the corner's, with degree 1.
  const auto c = m.cell(Scalar(5) * xm, -Scalar(5) * ym);
  EXPECT_EQ(c.i, 5u);
  EXPECT_EQ(c.j, 0u);
  EXPECT_EQ(c.weight[1][0], Scalar(1));
  EXPECT_EQ(c.weight[0][0] + c.weight[0][1] + c.weight[1][1], Scalar(0));
  EXPECT_EQ(m.refinement(Scalar(5) * xm, -Scalar(5) * ym, 2), m.table[2][6][0]);
  // The ramp saturates too: |x| + |y| >= 1 gives the ratio R T.
  EXPECT_EQ(m.ratio(big, big, 0),
            Scalar(1) + ((m.schedule_ratio[0] - Scalar(1)) * m.table[0][6][6] +
                         (m.table[0][6][6] - Scalar(1))));
}

TYPED_TEST(RuleTableTyped, CellNamesTheFourFiringRulesAndTheirDegrees) {
  // Every rule outside the cell has degree 0; the cell's weights are mu_i(x) nu_j(y).
  using Scalar = TypeParam;
  const std::uint64_t seed = 0xce11ULL;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  for (int n = 0; n < 50; ++n) {
    const auto m = random_model<Scalar, 7>(rng);
    for (int k = 0; k < 200; ++k) {
      const Scalar x = uniform<Scalar>(rng, -2.5, 2.5);
      const Scalar y = uniform<Scalar>(rng, -2.5, 2.5);
      const auto c = m.cell(x, y);
      ASSERT_LE(c.i, 5u);
      ASSERT_LE(c.j, 5u);
      Scalar sum = 0;
      for (std::size_t i = 0; i < 7; ++i)
        for (std::size_t j = 0; j < 7; ++j) {
          const long double want = membership(m.e_centers, i, x) * membership(m.ec_centers, j, y);
          const bool inside = i >= c.i && i <= c.i + 1 && j >= c.j && j <= c.j + 1;
          const Scalar got = inside ? c.weight[i - c.i][j - c.j] : Scalar(0);
          ASSERT_NEAR(static_cast<double>(got), static_cast<double>(want), tolerance<Scalar>())
              << "rule " << i << ", " << j << " at x=" << x << " y=" << y;
          sum += got;
        }
      ASSERT_NEAR(sum, 1.0, tolerance<Scalar>());
    }
  }
}

TYPED_TEST(RuleTableTyped, NonFiniteInputsAreAFaultWithZeroDelta) {
  using Scalar = TypeParam;
  const RuleTable<Scalar> m{{Scalar(2), Scalar(2), Scalar(2)}};
  auto ws = m.make_workspace();
  const Scalar nan = std::numeric_limits<Scalar>::quiet_NaN();
  const Scalar inf = std::numeric_limits<Scalar>::infinity();
  for (const auto& [x, y] : {std::pair{nan, Scalar(0)}, std::pair{Scalar(0), nan},
                             std::pair{inf, Scalar(0)}, std::pair{Scalar(0.1), -inf}}) {
    std::array<Scalar, 3> delta{Scalar(7), Scalar(7), Scalar(7)};
    EXPECT_EQ(m.infer(x, y, ws, delta), Status::NonFiniteInput) << x << ", " << y;
    EXPECT_EQ(delta, (std::array<Scalar, 3>{}));
  }
}

TEST(RuleTable, ValidRejectsAsymmetricUnorderedOrNonFiniteCentersAndNonPositiveRatios) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(RuleTable<double>{}.valid());
  const auto with_e = [](std::array<double, 7> c) {
    RuleTable<double> m;
    m.e_centers = c;
    return m.valid();
  };
  const auto with_ec = [](std::array<double, 7> c) {
    RuleTable<double> m;
    m.ec_centers = c;
    return m.valid();
  };
  EXPECT_TRUE(with_e({-3, -2, -0.5, 0, 0.5, 2, 3}));
  EXPECT_FALSE(with_e({-3, -2, -1, 0, 1, 2, 3.5})) << "asymmetric";
  EXPECT_FALSE(with_ec({-3, -2, -1, 0.1, 1, 2, 3})) << "center not 0";
  EXPECT_FALSE(with_e({-2, -3, -1, 0, 1, 3, 2})) << "unordered";
  EXPECT_FALSE(with_ec({-3, -1, -1, 0, 1, 1, 3})) << "repeated";
  EXPECT_FALSE(with_e({-inf, -2, -1, 0, 1, 2, inf})) << "infinite";
  EXPECT_FALSE(with_e({-3, nan, -1, 0, 1, nan, 3})) << "NaN";
  for (const double bad : {0.0, -0.5, nan, inf}) {
    RuleTable<double> m;
    m.schedule_ratio[1] = bad;
    EXPECT_FALSE(m.valid()) << "R = " << bad;
    RuleTable<double> t;
    t.table[2][3][4] = bad;
    EXPECT_FALSE(t.valid()) << "T = " << bad;
  }
  RuleTable<double> overflow;
  overflow.schedule_ratio[0] = 1e300;
  overflow.table[0][0][0] = 1e10;
  EXPECT_FALSE(overflow.valid()) << "R T overflows";
}

// Seeded ticks of two controllers: FuzzyPid<RuleTable> with T = 1 and S = K0, and
// FuzzyPid<GainSchedule> with S = K0 (R - 1) (the scheduled family). Returns the largest gain
// difference in units of eps max(K0, K) and the largest command difference in units of
// eps (|Kp e| + |I| + |Kd ec|), the rounding scale of the command's sum.
template <class Scalar>
std::pair<double, double> largest_differences(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  double worst = 0.0, worst_gain = 0.0;
  for (int n = 0; n < 200; ++n) {
    RuleTable<Scalar> table;
    for (auto& r : table.schedule_ratio)
      r = uniform<Scalar>(rng, 0.2, 4.0);
    table.e_centers = random_centers<Scalar, 7>(rng);
    table.ec_centers = random_centers<Scalar, 7>(rng);
    const GainSchedule<Scalar> schedule;
    FuzzyPidConfig<Scalar> c;
    c.pid.gains = {uniform<Scalar>(rng, 1, 100), uniform<Scalar>(rng, 0, 10),
                   uniform<Scalar>(rng, 0, 5)};
    c.error_scale = uniform<Scalar>(rng, 0.5, 20);
    c.error_rate_scale = uniform<Scalar>(rng, 0.1, 5);
    FuzzyPidConfig<Scalar> rules = c, scheduled = c;
    const auto& k0 = c.pid.gains;
    const auto& r = table.schedule_ratio;
    rules.output_scale = {k0.kp, k0.ki, k0.kd};
    scheduled.output_scale = {k0.kp * (r[0] - Scalar(1)), k0.ki * (r[1] - Scalar(1)),
                              k0.kd * (r[2] - Scalar(1))};
    FuzzyPid<Scalar, RuleTable<Scalar>> a(&table, rules);
    FuzzyPid<Scalar, GainSchedule<Scalar>> b(&schedule, scheduled);
    const Scalar dt = Scalar(0.001);
    for (int k = 0; k < 500; ++k) {
      fuzzypid::pid::Input<Scalar> in;
      in.setpoint = uniform<Scalar>(rng, -0.2, 0.2);
      in.measurement = uniform<Scalar>(rng, -0.2, 0.2);
      in.setpoint_rate = uniform<Scalar>(rng, -1, 1);
      in.measurement_rate = uniform<Scalar>(rng, -1, 1);
      EXPECT_EQ(a.update(in, dt), Status::Ok);
      EXPECT_EQ(b.update(in, dt), Status::Ok);
      const Scalar e = in.setpoint - in.measurement;
      const Scalar ec = in.setpoint_rate - in.measurement_rate;
      const double scale = std::fabs(b.gains().kp * e) + std::fabs(b.pid().integral()) +
                           std::fabs(b.gains().kd * ec);
      const double eps = std::numeric_limits<Scalar>::epsilon();
      worst = std::max(worst, std::fabs(double(a.output()) - double(b.output())) / (eps * scale));
      const std::array<Scalar, 3> ka{a.gains().kp, a.gains().ki, a.gains().kd};
      const std::array<Scalar, 3> kb{b.gains().kp, b.gains().ki, b.gains().kd};
      const std::array<Scalar, 3> nominal{k0.kp, k0.ki, k0.kd};
      for (std::size_t g = 0; g < 3; ++g)
        worst_gain = std::max(worst_gain, std::fabs(double(ka[g]) - double(kb[g])) /
                                              (eps * std::max(double(nominal[g]), double(kb[g]))));
    }
  }
  return {worst_gain, worst};
}

TEST(RuleTable, UnitTableInFuzzyPidGivesTheScheduledFamilysCommandsToAFewUlp) {
  const std::uint64_t seed = 0xf0770ULL;
  SCOPED_TRACE("seed " + std::to_string(seed));
  const auto [dg, d] = largest_differences<double>(seed);
  const auto [fg, f] = largest_differences<float>(seed);
  std::printf("largest gain difference: double %.3g, float %.3g (x eps max(K0, K))\n", dg, fg);
  std::printf("largest command difference: double %.3g, float %.3g (x eps (|Kp e|+|I|+|Kd ec|))\n",
              d, f);
  // K0 + K0 ((R - 1) w) against K0 + (K0 (R - 1)) w: the products round differently.
  EXPECT_LE(dg, 2.0);
  EXPECT_LE(fg, 2.0);
  EXPECT_LE(d, 4.0);
  EXPECT_LE(f, 4.0);
}

TEST(RuleTable, InferAllocatesNothing) {
  std::mt19937_64 rng(0xa110cULL);
  const auto m = random_model<double, 7>(rng);
  const auto mf = random_model<float, 7>(rng);
  auto ws = m.make_workspace();
  auto wsf = mf.make_workspace();
  std::array<double, 3> delta{};
  std::array<float, 3> deltaf{};
  double sink = 0.0;
  const std::uint64_t before = allocation_count();
  for (int k = 0; k < 100000; ++k) {
    const double x = -2.0 + 4e-5 * k, y = 1.5 - 3e-5 * k;
    sink += static_cast<double>(m.infer(x, y, ws, delta) == Status::Ok) + delta[0];
    sink +=
        static_cast<double>(mf.infer(float(y), float(x), wsf, deltaf) == Status::Ok) + deltaf[2];
  }
  EXPECT_EQ(allocation_count(), before) << "allocations in 200,000 inferences";
  EXPECT_TRUE(std::isfinite(sink));
}

}  // namespace
