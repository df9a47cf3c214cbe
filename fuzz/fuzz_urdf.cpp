// libFuzzer target for the URDF loader (robot::RobotModel::load, urdfdom + the KDL chain
// extraction). load() takes a path, so each input is written to one per-process file in /tmp and
// loaded from there. A successful load must give a model whose kinematics and dynamics can be
// evaluated without a sanitizer report; a failed one must say why.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "fuzzypid/robot/robot_model.hpp"
#include "fuzzypid/robot/types.hpp"

namespace {

const std::string& input_path() {
  static const std::string path = "/tmp/fuzzypid_fuzz_urdf_" + std::to_string(::getpid()) + ".urdf";
  return path;
}

bool write_file(const std::string& path, const std::uint8_t* data, std::size_t size) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) return false;
  const bool ok = std::fwrite(data, 1, size, f) == size;
  return std::fclose(f) == 0 && ok;
}

}  // namespace

// urdfdom 3.0 (Debian 12) leaks the link graph when a joint names the same link as parent and
// child: the link then owns itself through its child list (a shared_ptr cycle), and parseURDF
// drops the model on the "two root links" error without breaking it. The leak is inside urdfdom,
// before RobotModel::load sees any model, so leaks whose stack is in urdfdom are not reported.
// Found by this target; docs/robustness.md.
extern "C" const char* __lsan_default_suppressions() {  // NOLINT(bugprone-reserved-identifier)
  return "leak:liburdfdom_model.so\n";
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 1 << 16) return 0;
  if (!write_file(input_path(), data, size)) std::abort();
  const fuzzypid::robot::LoadResult result = fuzzypid::robot::RobotModel::load(input_path());
  if (!result.model) {
    if (result.error.empty()) std::abort();  // every failure must say why
    return 0;
  }
  const fuzzypid::robot::RobotModel& model = *result.model;
  const fuzzypid::robot::JointVector q = {0.1, -0.2, 0.3, -0.4, 0.5, -0.6};
  const fuzzypid::robot::JointVector qd = {0.5, 0.4, 0.3, 0.2, 0.1, 0.0};
  fuzzypid::robot::RobotData work(model);
  (void)model.forward_kinematics(q, work);
  (void)model.jacobian(q, work);
  (void)model.mass_matrix(q, work);
  (void)model.coriolis_torque(q, qd, work);
  (void)model.gravity_torque(q);
  (void)model.within_limits(q);
  return 0;
}
