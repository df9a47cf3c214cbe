// A linguistic variable: N fuzzy terms over a universe of discourse [min, max], and its
// fuzzification (crisp value -> N membership degrees).
#pragma once

#include <array>
#include <cstddef>
#include <limits>

#include "fuzzypid/fuzzy/membership.hpp"
#include "fuzzypid/scalar.hpp"

namespace fuzzypid::fuzzy {

// The membership degrees of one crisp value in each of a variable's N terms. Only the indices
// [first, last] can be non-zero; first > last means no term holds the value (e.g. NaN).
template <class Scalar, std::size_t N>
struct Fuzzified {
  std::array<Scalar, N> degree{};
  std::size_t first = 1;
  std::size_t last = 0;

  constexpr bool empty() const noexcept { return first > last; }
};

template <class Scalar, std::size_t N>
class LinguisticVariable {
  FUZZYPID_ASSERT_SCALAR(Scalar);
  static_assert(N >= 2, "a linguistic variable needs at least two terms");

 public:
  // N triangles with evenly spaced peaks min, min + h, ..., max (h = (max - min) / (N - 1)), each
  // reaching to its neighbours' peaks, so the degrees of any value in [min, max] sum to 1. The
  // outermost terms are shoulders: a value outside the universe saturates at the nearest edge
  // term with degree 1 instead of dropping out of every set. (Fig. 4 of the paper for N = 7 on
  // [-0.3, 0.3].) Requires min < max.
  static constexpr LinguisticVariable uniform(Scalar min, Scalar max) noexcept {
    LinguisticVariable v;
    v.min_ = min;
    v.max_ = max;
    v.uniform_ = true;
    const Scalar h = (max - min) / Scalar(N - 1);
    for (std::size_t k = 0; k < N; ++k)
      v.peak_[k] = k + 1 == N ? max : min + Scalar(k) * h;
    v.terms_[0] = Term<Scalar>::left_shoulder(v.peak_[0], v.peak_[1]);
    v.terms_[N - 1] = Term<Scalar>::right_shoulder(v.peak_[N - 2], v.peak_[N - 1]);
    for (std::size_t k = 1; k + 1 < N; ++k)
      v.terms_[k] = Term<Scalar>::triangle(v.peak_[k - 1], v.peak_[k], v.peak_[k + 1]);
    // 1/h, rounded down until (max - min) / h <= N - 1 in floating point, so that locate()'s
    // position t never passes the last peak (and equals N - 1 there when the rounding allows).
    Scalar r = Scalar(N - 1) / (max - min);
    for (int k = 0; k < 4 && (max - min) * r > Scalar(N - 1); ++k)
      r -= r * std::numeric_limits<Scalar>::epsilon();
    v.inverse_step_ = r;
    return v;
  }

  // Arbitrary terms on [min, max]. Fuzzification evaluates every term; no saturation is added, so
  // give the outermost terms shoulder shapes if inputs may leave the universe.
  static constexpr LinguisticVariable custom(Scalar min, Scalar max,
                                             const std::array<Term<Scalar>, N>& terms) noexcept {
    LinguisticVariable v;
    v.min_ = min;
    v.max_ = max;
    v.uniform_ = false;
    v.terms_ = terms;
    for (std::size_t k = 0; k < N; ++k)
      v.peak_[k] = terms[k].center();
    return v;
  }

  static constexpr std::size_t size() noexcept { return N; }
  constexpr Scalar min() const noexcept { return min_; }
  constexpr Scalar max() const noexcept { return max_; }
  constexpr const Term<Scalar>& term(std::size_t k) const noexcept { return terms_[k]; }
  constexpr const std::array<Term<Scalar>, N>& terms() const noexcept { return terms_; }
  // The term centers (peaks of a uniform partition), in the universe's units.
  constexpr const std::array<Scalar, N>& centers() const noexcept { return peak_; }
  constexpr bool is_uniform() const noexcept { return uniform_; }

  // True when min < max (both finite) and every term is a valid shape.
  constexpr bool valid() const noexcept {
    if (!(detail::is_finite(min_) && detail::is_finite(max_) && min_ < max_)) return false;
    for (const auto& t : terms_)
      if (!t.valid()) return false;
    return true;
  }

  // Membership degrees of x in every term. For a uniform partition at most two adjacent terms are
  // non-zero and they are found in O(1); otherwise every term is evaluated.
  Fuzzified<Scalar, N> fuzzify(Scalar x) const noexcept {
    Fuzzified<Scalar, N> out;
    fuzzify_into(x, out);
    return out;
  }

  // The two adjacent terms k, k + 1 of a uniform partition whose interval holds x, and x's
  // degrees in them (every other term's degree is 0). Outside the universe it is the edge term
  // with degree 1 and its neighbour with degree 0. A term whose degree here is not > 0 does not
  // hold x.
  struct Adjacent {
    std::size_t k;
    Scalar lower;  // degree of term k
    Scalar upper;  // degree of term k + 1
  };

  // Requires a uniform partition and x not NaN (an infinity saturates). O(1), no division, no
  // table look-up and no data-dependent branch: with x clamped into the universe (where the edge
  // term holds it with degree 1), t = (x - min) / h is x's position in steps, k = floor(t) the
  // interval, and the triangle formulas on [peak_k, peak_k+1] reduce to upper = t - k and
  // lower = 1 - upper (uniform peaks; equal to evaluating the terms up to rounding, about
  // N ulp). The step's reciprocal is precomputed by uniform().
  constexpr Adjacent locate(Scalar x) const noexcept {
    const Scalar t = (detail::clamp(x, min_, max_) - min_) * inverse_step_;  // in [0, N - 1]
    // A signed conversion: t is small and non-negative, and int needs no range fix-up.
    const int floor_t = static_cast<int>(t);
    const std::size_t k = floor_t < int(N - 2) ? static_cast<std::size_t>(floor_t) : N - 2;
    const Scalar upper = t - static_cast<Scalar>(static_cast<int>(k));
    return {k, Scalar(1) - upper, upper};
  }

 private:
  // fuzzify() written into `out`, which must be default-constructed (all degrees 0, empty span).
  void fuzzify_into(Scalar x, Fuzzified<Scalar, N>& out) const noexcept {
    if (x != x) return;
    if (!uniform_) {
      fuzzify_each(x, out);
      return;
    }
    const Adjacent a = locate(x);
    out.degree[a.k] = a.lower;
    out.degree[a.k + 1] = a.upper;
    out.first = a.lower > Scalar(0) ? a.k : a.k + 1;
    out.last = a.upper > Scalar(0) ? a.k + 1 : a.k;
  }

  // Every term evaluated (custom partitions); out of line so the uniform path inlines.
  [[gnu::noinline]] void fuzzify_each(Scalar x, Fuzzified<Scalar, N>& out) const noexcept {
    for (std::size_t k = 0; k < N; ++k) {
      const Scalar d = terms_[k](x);
      out.degree[k] = d;
      if (d > Scalar(0)) {
        if (out.empty()) out.first = k;
        out.last = k;
      }
    }
  }

  std::array<Term<Scalar>, N> terms_{};
  std::array<Scalar, N> peak_{};
  Scalar min_{};
  Scalar max_{};
  Scalar inverse_step_{};  // 1 / h (rounded down, see uniform()), for locate()
  bool uniform_ = false;
};

}  // namespace fuzzypid::fuzzy
