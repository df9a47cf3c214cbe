// Uses fuzzypid through add_subdirectory(): one tick of the paper's fuzzy PID, and the robot
// model from the vendored tree's bundled URDF.
#include <cstdio>

#include <fuzzypid/fuzzypid.hpp>
#include <fuzzypid/robot/robot_model.hpp>

int main() {
  auto controller = fuzzypid::paper::make_joint_controller<double, 6>();
  fuzzypid::supervisor::JointInput<double, 6> in;
  in.desired_position_rad = {0.1, 0, 0, 0, 0, 0};
  const auto out = controller.step(in, 0.05);
  const fuzzypid::robot::LoadResult loaded =
      fuzzypid::robot::RobotModel::load(fuzzypid::robot::default_urdf_path());
  if (!loaded.model) {
    std::fprintf(stderr, "load failed: %s\n", loaded.error.c_str());
    return 1;
  }
  return out.status == fuzzypid::Status::Ok && out.output[0] > 0.0 ? 0 : 1;
}
