// Uses the installed robot part: loads the installed ER50-C20 description (argv[1]) and checks that
// forward kinematics of q = 0 is finite and away from the base.
#include <cmath>
#include <cstdio>

#include <fuzzypid/robot/robot_model.hpp>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const fuzzypid::robot::LoadResult loaded = fuzzypid::robot::RobotModel::load(argv[1]);
  if (!loaded.model) {
    std::fprintf(stderr, "load failed: %s\n", loaded.error.c_str());
    return 1;
  }
  fuzzypid::robot::RobotData data(*loaded.model);
  const fuzzypid::robot::Pose pose = loaded.model->forward_kinematics({0, 0, 0, 0, 0, 0}, data);
  const double reach_m = pose.position_m.norm();
  std::printf("reach at q = 0: %.3f m\n", reach_m);
  return std::isfinite(reach_m) && reach_m > 0.5 ? 0 : 1;
}
