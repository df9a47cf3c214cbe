// Compiled (not run) for a Cortex-M4F with -fno-exceptions -fno-rtti and Scalar = float, to prove
// the core fits a microcontroller: no exceptions, no RTTI, no heap, no OS.
#include "fuzzypid/fuzzypid.hpp"

namespace {
fuzzypid::control::JointController<float, 6> controller{fuzzypid::control::FuzzyPid<float>(
    fuzzypid::paper::make_system<float>(), fuzzypid::control::paper_config<float>())};
}  // namespace

extern "C" float fuzzypid_tick(const float* desired, const float* measured, float* command) {
  std::array<float, 6> qd{}, q{}, zero{};
  for (int i = 0; i < 6; ++i) {
    qd[i] = desired[i];
    q[i] = measured[i];
  }
  const auto out = controller.step(qd, zero, q, zero, 0.05f);
  for (int i = 0; i < 6; ++i)
    command[i] = out.command[i];
  return fuzzypid::is_fault(out.status) ? -1.0f : 0.0f;
}
