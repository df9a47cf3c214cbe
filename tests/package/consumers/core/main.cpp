// Uses the installed headers: one tick of the paper's fuzzy PID on six joints.
#include <fuzzypid/fuzzypid.hpp>

int main() {
  fuzzypid::control::JointController<double, 6> controller;
  const std::array<double, 6> desired{0.1, 0, 0, 0, 0, 0};
  const std::array<double, 6> zero{};
  const auto out = controller.step(desired, zero, zero, zero, 0.05);
  // Kp e = 4 * 0.1 plus the retuned gain's share: the command must be positive and finite.
  return out.status == fuzzypid::Status::Ok && out.command[0] > 0.0 ? 0 : 1;
}
