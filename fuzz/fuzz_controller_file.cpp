// libFuzzer target for the two TOML readers: the controller-file loader (fuzzypid/controller_file)
// and the condition-file reader (sim/condition_set.hpp, with the robot, path and plant keys). Any
// input must be accepted or rejected with a positioned error, never crash; an accepted controller
// file must round-trip exactly (write, read, write gives the same text) and build a controller; an
// accepted condition file must hold only conditions that validate. One target for both keeps the
// CI's fuzz time as it was.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "fuzzypid/controller/joint_controllers.hpp"
#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid/sim/condition_set.hpp"

namespace {

void check_conditions(std::string_view text) {
  fuzzypid::sim::ConditionFile file;
  fuzzypid::FileError error;
  if (!fuzzypid::sim::parse_conditions(text, "dir/fuzz.toml", file, error)) {
    if (error.file != "dir/fuzz.toml" || error.line < 1 || error.column < 1 ||
        error.message.empty())
      std::abort();
    return;
  }
  if (file.sets.empty()) std::abort();
  for (const auto& set : file.sets) {
    if (set.conditions.empty()) std::abort();
    for (const auto& c : set.conditions)
      if (!c.validate().empty()) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace cf = fuzzypid::controller_file;
  namespace controller = fuzzypid::controller;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  check_conditions(text);
  cf::ControllerFile file;
  fuzzypid::FileError error;
  if (!cf::parse(text, "fuzz.toml", file, error)) {
    if (error.file != "fuzz.toml" || error.line < 1 || error.column < 1 || error.message.empty())
      std::abort();
    return 0;
  }
  const std::string written = cf::to_toml(file);
  cf::ControllerFile back;
  if (!cf::parse(written, "written.toml", back, error)) std::abort();
  if (cf::to_toml(back) != written) std::abort();
  const controller::ControllerSpec& spec = file.controller;
  std::string build_error;
  if (!controller::JointControllers::create(spec, controller::Vector{1, 1, 1, 1, 1, 1},
                                            build_error))
    std::abort();
  return 0;
}
