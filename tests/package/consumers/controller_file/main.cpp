// Uses the installed controller_file part: loads an installed controller file (argv[1]) and runs
// one tick of the six joints it describes.
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include <fuzzypid/controller/joint_controllers.hpp>
#include <fuzzypid/controller_file/controller_file.hpp>

int main(int argc, char** argv) {
  namespace cf = fuzzypid::controller_file;
  namespace controller = fuzzypid::controller;
  if (argc != 2) return 2;
  controller::ControllerSpec spec;
  fuzzypid::FileError error;
  if (!cf::load(argv[1], spec, error)) {
    std::fprintf(stderr, "%s\n", error.to_string().c_str());
    return 1;
  }
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
