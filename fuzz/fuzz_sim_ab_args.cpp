// libFuzzer target for sim_ab's command-line parser (apps/sim_ab/options.cpp, the function
// sim_ab's main() calls). The input is split at NUL bytes into argv[1..]. Accepted options must
// leave finite numbers and valid conditions behind.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "../apps/sim_ab/options.hpp"
#include "fuzz_args.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 4096) return 0;
  const fuzzypid::fuzz::CommandLine line("sim_ab", data, size);
  fuzzypid::sim_ab::Options o;
  const auto rc = fuzzypid::sim_ab::parse(line.argc(), line.argv(), o);
  if (rc == fuzzypid::sim_ab::ParseResult::Run) {
    const auto& e = o.experiment;
    if (!e.gains.finite() || !std::isfinite(e.error_scale) || !std::isfinite(e.error_rate_scale) ||
        e.gains.kp < 0 || e.gains.ki < 0 || e.gains.kd < 0)
      std::abort();
    for (const auto& c : fuzzypid::sim_ab::scenario_conditions(o))
      if (!c.validate().empty()) std::abort();
  }
  return 0;
}
