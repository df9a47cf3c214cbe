// libFuzzer target for rt_loop's command-line parser (apps/rt_loop/options.cpp, the function
// rt_loop's main() calls). The input is split at NUL bytes into argv[1..]. Accepted options must
// leave what the loop relies on: a finite period in range, a controller dt in --dt's range
// (given or derived from the period), a known controller, and at most kMaxCsvTicks ticks when
// every tick is buffered for --csv, and a --csv path that check_output_path accepted
// (apps/common/output_files.hpp): an existing target is a regular file and not the controller
// file. The path checks only read the file system (stat, lstat, realpath, faccessat).
#include <sys/stat.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "../apps/rt_loop/options.hpp"
#include "fuzz_args.hpp"

namespace rt = fuzzypid::rt_loop;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 4096) return 0;
  const fuzzypid::fuzz::CommandLine line("rt_loop", data, size);
  rt::Options o;
  const auto code = rt::parse(line.argc(), line.argv(), o);
  if (code) {
    if (*code != 0 && *code != 2) std::abort();  // --help or a usage error, nothing else
    return 0;
  }
  if (!std::isfinite(o.period_ms) || o.period_ms < 0.0 || o.period_ms > rt::kMaxPeriodMs)
    std::abort();
  if (o.dt_s && !(*o.dt_s >= rt::kMinDtS && *o.dt_s <= rt::kMaxDtS)) std::abort();
  const double dt = o.controller_dt_s();
  if (!(dt >= rt::kMinDtS && dt <= rt::kMaxDtS)) std::abort();
  if (o.ticks && *o.ticks == 0) std::abort();
  if (!o.csv.empty() && o.ticks && *o.ticks > rt::kMaxCsvTicks) std::abort();
  const std::string& c = o.controller;
  const bool file = c.size() > 5 && c.compare(c.size() - 5, 5, ".toml") == 0;
  if (c != "pid" && c != "fuzzy" && !file) std::abort();
  if (o.cpu && *o.cpu < 0) std::abort();
  if (!o.csv.empty()) {
    struct stat target {};
    if (::stat(o.csv.c_str(), &target) == 0) {
      if (!S_ISREG(target.st_mode)) std::abort();  // a folder, device, FIFO or socket
      struct stat input {};
      if (file && ::stat(c.c_str(), &input) == 0 && input.st_dev == target.st_dev &&
          input.st_ino == target.st_ino)
        std::abort();  // the controller file itself
    }
  }
  return 0;
}
