// The number types the core is written for, and the few numeric helpers it needs without <cmath>
// calls that are not constexpr in C++17.
#pragma once

#include <limits>
#include <type_traits>

namespace fuzzypid {

// float for microcontrollers with a single-precision FPU, double for PCs.
template <class Scalar>
inline constexpr bool is_supported_scalar_v =
    std::is_same_v<Scalar, float> || std::is_same_v<Scalar, double> ||
    std::is_same_v<Scalar, long double>;

#define FUZZYPID_ASSERT_SCALAR(Scalar)                     \
  static_assert(::fuzzypid::is_supported_scalar_v<Scalar>, \
                "fuzzypid: Scalar must be float, double or long double")

namespace detail {

// constexpr, exception-free finiteness test (std::isfinite is not constexpr in C++17). GCC and
// Clang's builtin is constexpr and compiles to |x| <= max without branches (one mask, one quiet
// compare), about half the instructions of the portable form, which the control tick calls a
// dozen times per joint. Portable form: NaN fails the self-comparison, infinities the range test.
template <class Scalar>
constexpr bool is_finite(Scalar x) noexcept {
#if defined(__GNUC__) || defined(__clang__)
  return __builtin_isfinite(x);
#else
  return x == x && x <= std::numeric_limits<Scalar>::max() &&
         x >= std::numeric_limits<Scalar>::lowest();
#endif
}

// min and max are written so that they compile to one minsd/maxsd (vminss/vmaxss on a Cortex-M4F
// FPU: vcmp + vsel-free moves), without branches; a NaN in `a` is passed through.
template <class Scalar>
constexpr Scalar min(Scalar a, Scalar b) noexcept {
  return b < a ? b : a;
}

template <class Scalar>
constexpr Scalar max(Scalar a, Scalar b) noexcept {
  return a < b ? b : a;
}

// x clamped into [lo, hi] (requires lo <= hi); a NaN x stays NaN. Written as min(max()) so it is
// two branch-free instructions where the target has them.
template <class Scalar>
constexpr Scalar clamp(Scalar x, Scalar lo, Scalar hi) noexcept {
  return min(max(x, lo), hi);
}

template <class Scalar>
constexpr Scalar abs(Scalar x) noexcept {
  return x < Scalar(0) ? -x : x;
}

template <class Scalar>
constexpr Scalar infinity() noexcept {
  return std::numeric_limits<Scalar>::infinity();
}

}  // namespace detail
}  // namespace fuzzypid
