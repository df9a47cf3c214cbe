// Seeded uniform draws that are the same on every standard library. std::mt19937_64's output is
// fixed by the standard; std::uniform_real_distribution's algorithm is not ([rand.dist.uni.real]),
// so a seeded test would draw other inputs on libc++ than on libstdc++. Standard library only;
// private like the rest of support/.
#pragma once

#include <random>

namespace fuzzypid::support {

// A draw in [min, max]: min + (max - min) * u, with u the top 53 bits of one engine output over
// 2^53 (u in [0, 1)). Rounding can give max itself, as the standard distribution can.
template <class Real = double>
class UniformReal {
 public:
  constexpr UniformReal(Real min, Real max) noexcept : min_(min), max_(max) {}

  Real operator()(std::mt19937_64& rng) const {
    const double u = static_cast<double>(rng() >> 11U) * 0x1.0p-53;
    const auto lo = static_cast<double>(min_);
    return static_cast<Real>(lo + (static_cast<double>(max_) - lo) * u);
  }

 private:
  Real min_;
  Real max_;
};

}  // namespace fuzzypid::support
