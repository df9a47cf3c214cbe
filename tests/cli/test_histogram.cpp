// cli::Histogram (apps/common/histogram.hpp): quantiles to bucket resolution against a sorted copy.
#include "histogram.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace fuzzypid::cli {
namespace {

TEST(Histogram, EmptyReportsZeros) {
  const Histogram h;
  EXPECT_EQ(h.count(), 0u);
  EXPECT_EQ(h.min(), 0u);
  EXPECT_EQ(h.max(), 0u);
  EXPECT_EQ(h.quantile(0.5), 0u);
}

TEST(Histogram, SmallValuesAreExactAndNegativesCountAsZero) {
  Histogram h;
  for (std::int64_t v : {-5, 0, 1, 2, 3, 127})
    h.record(v);
  EXPECT_EQ(h.count(), 6u);
  EXPECT_EQ(h.min(), 0u);
  EXPECT_EQ(h.max(), 127u);
  EXPECT_EQ(h.quantile(0.5), 1u);  // 0, 0, 1 | 2, 3, 127
  EXPECT_EQ(h.quantile(1.0), 127u);
}

// Quantiles of log-uniform durations from 10 ns to 10 s are within the 1/64 bucket resolution of
// the exact order statistic, and never outside [min, max].
TEST(Histogram, QuantilesAreWithinTheBucketResolution) {
  const std::uint64_t seed = 20261201;
  std::printf("[ seed     ] %llu\n", static_cast<unsigned long long>(seed));
  std::mt19937_64 rng(seed);
  Histogram h;
  std::vector<std::uint64_t> values;
  for (int k = 0; k < 100000; ++k) {
    const double exponent = 1.0 + 9.0 * static_cast<double>(rng() >> 11) * 0x1.0p-53;
    const auto v = static_cast<std::uint64_t>(std::pow(10.0, exponent));
    values.push_back(v);
    h.record(static_cast<std::int64_t>(v));
  }
  std::sort(values.begin(), values.end());
  EXPECT_EQ(h.min(), values.front());
  EXPECT_EQ(h.max(), values.back());
  for (double q : {0.01, 0.5, 0.9, 0.99, 0.999}) {
    const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size())));
    const double exact = static_cast<double>(values[rank - 1]);
    const double got = static_cast<double>(h.quantile(q));
    EXPECT_GE(got, exact) << "q = " << q;
    EXPECT_LE(got, exact * (1.0 + 1.0 / 64.0) + 1.0) << "q = " << q;
  }
}

}  // namespace
}  // namespace fuzzypid::cli
