// Uses fuzzypid through add_subdirectory(): one tick of the paper's fuzzy PID, and the robot
// model from the vendored tree's bundled URDF.
#include <cstdio>

#include <fuzzypid/fuzzypid.hpp>
#include <fuzzypid/robot/robot_model.hpp>

int main() {
  fuzzypid::control::JointController<double, 6> controller;
  const std::array<double, 6> desired{0.1, 0, 0, 0, 0, 0};
  const std::array<double, 6> zero{};
  const auto out = controller.step(desired, zero, zero, zero, 0.05);
  const fuzzypid::robot::LoadResult loaded =
      fuzzypid::robot::RobotModel::load(fuzzypid::robot::default_urdf_path());
  if (!loaded.model) {
    std::fprintf(stderr, "load failed: %s\n", loaded.error.c_str());
    return 1;
  }
  return out.status == fuzzypid::Status::Ok && out.command[0] > 0.0 ? 0 : 1;
}
