// The sim's one seeded random generator: std::mt19937_64 (its sequence is fixed by the standard)
// with uniform and normal draws written out here, so that a seed gives the same noise and the same
// Monte-Carlo conditions with every standard library (std::uniform_real_distribution and
// std::normal_distribution are implementation-defined).
#pragma once

#include <cmath>
#include <cstdint>
#include <random>

namespace fuzzypid::sim {

class Random {
 public:
  explicit Random(std::uint64_t seed) noexcept : engine_(seed) {}

  // Uniform in [0, 1), 53 random bits.
  double uniform() noexcept { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  // Uniform in [lo, hi).
  double uniform(double lo, double hi) noexcept { return lo + (hi - lo) * uniform(); }

  // sigma * N(0, 1) by Box-Muller (two draws per sample); sigma = 0 returns 0 without drawing.
  double normal(double sigma) noexcept {
    if (sigma == 0.0) return 0.0;
    constexpr double kTwoPi = 6.283185307179586;
    const double u1 = (static_cast<double>(engine_() >> 11) + 1.0) * 0x1.0p-53;  // (0, 1]
    const double u2 = uniform();
    return sigma * std::sqrt(-2.0 * std::log(u1)) * std::cos(kTwoPi * u2);
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace fuzzypid::sim
