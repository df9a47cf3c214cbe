// PID gains in the parallel form of Eq. 2: u = Kp e + Ki * integral(e dt) + Kd de/dt.
#pragma once

#include "fuzzypid/scalar.hpp"

namespace fuzzypid::pid {

// With e in rad and u in N·m: kp in N·m/rad, ki in N·m/(rad·s), kd in N·m·s/rad.
template <class Scalar>
struct Gains {
  Scalar kp = Scalar(0);
  Scalar ki = Scalar(0);
  Scalar kd = Scalar(0);

  constexpr bool finite() const noexcept {
    return detail::is_finite(kp) && detail::is_finite(ki) && detail::is_finite(kd);
  }
};

template <class Scalar>
constexpr bool operator==(const Gains<Scalar>& a, const Gains<Scalar>& b) noexcept {
  return a.kp == b.kp && a.ki == b.ki && a.kd == b.kd;
}
template <class Scalar>
constexpr bool operator!=(const Gains<Scalar>& a, const Gains<Scalar>& b) noexcept {
  return !(a == b);
}

}  // namespace fuzzypid::pid
