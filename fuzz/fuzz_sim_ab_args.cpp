// libFuzzer target for sim_ab's command-line parser (apps/sim_ab/options.cpp, the function
// sim_ab's main() calls). The input is split at NUL bytes into argv[1..]. Accepted options must
// leave finite numbers and valid conditions behind.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "../apps/sim_ab/options.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 4096) return 0;
  std::vector<std::string> args{"sim_ab"};
  std::string current;
  for (std::size_t k = 0; k < size; ++k) {
    if (data[k] == 0) {
      args.push_back(current);
      current.clear();
    } else {
      current.push_back(static_cast<char>(data[k]));
    }
  }
  if (!current.empty()) args.push_back(current);
  std::vector<const char*> argv;
  for (const std::string& a : args)
    argv.push_back(a.c_str());
  argv.push_back(nullptr);

  // --help and usage errors print; keep the fuzzer's output readable.
  static std::FILE* const null_out = std::freopen("/dev/null", "w", stdout);
  (void)null_out;
  fuzzypid::sim_ab::Options o;
  const auto rc = fuzzypid::sim_ab::parse(static_cast<int>(args.size()), argv.data(), o);
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
