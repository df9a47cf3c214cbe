// libFuzzer target for sim_ab's command-line parser. The parser lives in an anonymous namespace of
// apps/sim_ab/main.cpp, so that file is compiled into this one with its main() renamed. The input
// is split at NUL bytes into argv[1..]. Accepted options must leave finite numbers behind.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#define main sim_ab_main
#include "../apps/sim_ab/main.cpp"
#undef main

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
  std::vector<char*> argv;
  for (std::string& a : args)
    argv.push_back(a.data());
  argv.push_back(nullptr);

  Options o;
  const int rc = parse(static_cast<int>(args.size()), argv.data(), o);
  if (rc != 0 && rc != 2 && rc != -1) std::abort();
  if (rc == 0) {
    const auto& e = o.experiment;
    if (!e.gains.finite() || !std::isfinite(e.error_scale) || !std::isfinite(e.error_rate_scale) ||
        !std::isfinite(e.initial_error_rad) || e.gains.kp < 0 || e.gains.ki < 0 || e.gains.kd < 0)
      std::abort();
  }
  return 0;
}
