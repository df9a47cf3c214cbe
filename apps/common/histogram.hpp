// Fixed-bucket log-linear histogram of non-negative durations in ns, for measuring inside a
// real-time loop: recording is two shifts and an increment, never allocates, never throws.
//
// Exact below 128 ns, then 64 buckets per power of two (relative resolution 1/64, about 1.6 %),
// up to 2^40 ns (18 min); larger values land in the last bucket. Negative values count as 0. min
// and max are kept exactly. About 18 kB: give it static storage in a real-time program.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace fuzzypid::cli {

class Histogram {
 public:
  static constexpr int kSubBits = 6;
  static constexpr std::uint64_t kSub = std::uint64_t{1} << kSubBits;  // 64
  static constexpr int kMaxBits = 40;
  static constexpr std::size_t kBuckets = (kMaxBits - kSubBits + 1) * kSub;

  void record(std::int64_t ns) noexcept {
    const std::uint64_t v = ns < 0 ? 0 : static_cast<std::uint64_t>(ns);
    ++counts_[index(v)];
    ++n_;
    if (v < min_) min_ = v;
    if (v > max_) max_ = v;
  }

  std::uint64_t count() const noexcept { return n_; }
  std::uint64_t min() const noexcept { return n_ == 0 ? 0 : min_; }
  std::uint64_t max() const noexcept { return max_; }

  // The smallest v such that at least a fraction q of the samples are <= v, to bucket resolution
  // (the bucket's upper edge, clamped into [min, max]). 0 when empty.
  std::uint64_t quantile(double q) const noexcept {
    if (n_ == 0) return 0;
    const auto rank = static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(n_)));
    const std::uint64_t target = rank == 0 ? 1 : rank;
    std::uint64_t seen = 0;
    for (std::size_t i = 0; i < kBuckets; ++i) {
      seen += counts_[i];
      if (seen >= target) {
        const std::uint64_t hi = upper_edge(i);
        return hi < min_ ? min_ : (hi > max_ ? max_ : hi);
      }
    }
    return max_;
  }

 private:
  static std::size_t index(std::uint64_t v) noexcept {
    if (v < 2 * kSub) return static_cast<std::size_t>(v);
    if (v >= (std::uint64_t{1} << kMaxBits)) return kBuckets - 1;
    const int msb = 63 - __builtin_clzll(v);
    const int shift = msb - kSubBits;
    return static_cast<std::size_t>((static_cast<std::uint64_t>(shift) + 1) * kSub +
                                    ((v >> shift) - kSub));
  }
  static std::uint64_t upper_edge(std::size_t i) noexcept {
    if (i < 2 * kSub) return i;
    const std::uint64_t shift = i / kSub - 1;
    const std::uint64_t sub = i % kSub + kSub;
    return ((sub + 1) << shift) - 1;
  }

  std::array<std::uint64_t, kBuckets> counts_{};
  std::uint64_t n_ = 0;
  std::uint64_t min_ = UINT64_MAX;
  std::uint64_t max_ = 0;
};

}  // namespace fuzzypid::cli
