// A gain schedule written as a supervisor: no fuzzy logic, the fair competitor of the paper's
// fuzzy supervisor (docs/tuning.md).
//
// FuzzyPid hands every supervisor the scaled inputs (x, y) = (Ke e, Kec ec) and applies
// K = K0 + S dK (Eq. 6). This supervisor returns the same correction for all three gains,
//
//     dKp = dKi = dKd = w(x, y) = min(1, |x| + |y|),
//
// a ramp that is 0 on the path (e = ec = 0) and saturates at 1 where Ke|e| + Kec|ec| >= 1. With
// the output scales S = K0 (R - 1) (controller_file's `scheduled` family) the gains move linearly
// from the small-error set K0 to the large-error set K0 R, each gain up (R > 1) or down (R < 1):
// eight free parameters (K0, Ke, Kec, R), the same count and the same inputs as the fuzzy PID. The
// difference to the fuzzy form is only the shape of dK(e, ec): one even, monotone ramp here, the
// paper's 49-rule tables (roughly odd in e, ec) there.
//
// The model is immutable and has no per-joint state (Workspace is empty); controllers keep a
// non-owning pointer to it, so it must outlive them.
#pragma once

#include <array>

#include "fuzzypid/scalar.hpp"
#include "fuzzypid/status.hpp"

namespace fuzzypid::supervisor {

template <class Scalar>
class GainSchedule {
  FUZZYPID_ASSERT_SCALAR(Scalar);

 public:
  struct Workspace {};

  Workspace make_workspace() const noexcept { return {}; }

  // w(x, y) = min(1, |x| + |y|) for all three outputs. Non-finite inputs are a fault (delta = 0).
  [[nodiscard]] Status infer(Scalar e, Scalar ec, Workspace& /*ws*/,
                             std::array<Scalar, 3>& delta) const noexcept {
    if (!detail::is_finite(e) || !detail::is_finite(ec)) {
      delta = {Scalar(0), Scalar(0), Scalar(0)};
      return Status::NonFiniteInput;
    }
    const Scalar a = (e < Scalar(0) ? -e : e) + (ec < Scalar(0) ? -ec : ec);
    const Scalar w = a < Scalar(1) ? a : Scalar(1);
    delta = {w, w, w};
    return Status::Ok;
  }
};

}  // namespace fuzzypid::supervisor
