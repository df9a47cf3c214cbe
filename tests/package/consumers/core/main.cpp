// Uses the installed headers: one tick of the paper's fuzzy PID on six joints.
#include <fuzzypid/fuzzypid.hpp>

int main() {
  auto controller = fuzzypid::paper::make_joint_controller<double, 6>();
  fuzzypid::supervisor::JointInput<double, 6> in;
  in.desired_position_rad = {0.1, 0, 0, 0, 0, 0};
  const auto out = controller.step(in, 0.05);
  // Kp e = 4 * 0.1 plus the retuned gain's share: the command must be positive and finite.
  return out.status == fuzzypid::Status::Ok && out.output[0] > 0.0 ? 0 : 1;
}
