// Compiled (not run) for a Cortex-M4F with -fno-exceptions -fno-rtti and Scalar = float, to prove
// the core fits a microcontroller: no exceptions, no RTTI, no heap, no OS.
#include "fuzzypid/fuzzypid.hpp"

namespace {
auto controller = fuzzypid::paper::make_joint_controller<float, 6>();
}  // namespace

extern "C" float fuzzypid_tick(const float* desired, const float* measured, float* command) {
  fuzzypid::control::JointInput<float, 6> in;
  for (int i = 0; i < 6; ++i) {
    in.desired_position_rad[i] = desired[i];
    in.measured_position_rad[i] = measured[i];
  }
  const auto out = controller.step(in, 0.05f);
  for (int i = 0; i < 6; ++i)
    command[i] = out.torque_nm[i];
  return fuzzypid::is_fault(out.status) ? -1.0f : 0.0f;
}
