// The supervisor of the sixth family this test build adds (p_schedule.hpp): the gain schedule's
// ramp w(x, y) = min(1, |x| + |y|) on the proportional gain only; the integral and derivative
// gains stay at K0. A supervisor as supervisor/supervisor.hpp defines one: immutable, no per-joint
// state.
#pragma once

#include <array>

#include "fuzzypid/scalar.hpp"
#include "fuzzypid/status.hpp"

namespace fuzzypid_test {

template <class Scalar>
class ProportionalRamp {
 public:
  struct Workspace {};

  Workspace make_workspace() const noexcept { return {}; }

  // dKp = w(x, y), dKi = dKd = 0. Non-finite inputs are a fault (delta = 0).
  [[nodiscard]] fuzzypid::Status infer(Scalar e, Scalar ec, Workspace& /*ws*/,
                                       std::array<Scalar, 3>& delta) const noexcept {
    if (!fuzzypid::detail::is_finite(e) || !fuzzypid::detail::is_finite(ec)) {
      delta = {Scalar(0), Scalar(0), Scalar(0)};
      return fuzzypid::Status::NonFiniteInput;
    }
    const Scalar a = (e < Scalar(0) ? -e : e) + (ec < Scalar(0) ? -ec : ec);
    delta = {a < Scalar(1) ? a : Scalar(1), Scalar(0), Scalar(0)};
    return fuzzypid::Status::Ok;
  }
};

}  // namespace fuzzypid_test
