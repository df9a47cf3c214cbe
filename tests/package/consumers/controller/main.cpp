// Uses the installed controller part without any file format: describes the paper's fuzzy PID in
// code and runs one tick of the six joints.
#include <cstdio>
#include <limits>
#include <string>

#include <fuzzypid/controller/joint_controllers.hpp>

int main() {
  namespace controller = fuzzypid::controller;
  const controller::ControllerSpec spec = controller::paper_fuzzy();
  controller::Vector limit;
  limit.fill(std::numeric_limits<double>::infinity());
  std::string message;
  auto joints = controller::JointControllers::create(spec, limit, message);
  if (!joints) {
    std::fprintf(stderr, "%s\n", message.c_str());
    return 1;
  }
  controller::Input in;
  in.desired_position_rad = {0.1, 0, 0, 0, 0, 0};
  const controller::Command out = joints->step(in, spec.units.tick_s);
  std::printf("%s: u1 = %.6g\n", controller::to_string(spec.family), out.output[0]);
  return out.status == fuzzypid::Status::Ok && out.output[0] > 0.0 ? 0 : 1;
}
