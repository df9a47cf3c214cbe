// libFuzzer target for the controller-file loader (fuzzypid/controller_file). Any input must be
// accepted or rejected with a positioned error, never crash; an accepted file must round-trip
// exactly (write, read, write gives the same text) and build a controller.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid/controller_file/joint_controllers.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace cf = fuzzypid::controller_file;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  cf::ControllerSpec spec;
  cf::Error error;
  if (!cf::parse(text, "fuzz.toml", spec, error)) {
    if (error.file != "fuzz.toml" || error.line < 1 || error.column < 1 || error.message.empty())
      std::abort();
    return 0;
  }
  const std::string written = cf::to_toml(spec);
  cf::ControllerSpec back;
  if (!cf::parse(written, "written.toml", back, error)) std::abort();
  if (cf::to_toml(back) != written) std::abort();
  std::string build_error;
  if (!cf::JointControllers::create(spec, cf::Vector{1, 1, 1, 1, 1, 1}, build_error))
    std::abort();
  return 0;
}
