// rt_loop's command line (CLI11): the loop's period, the controller's dt, the run length, the
// controller, the CSV and the real-time settings. Kept apart from main() (whose binary replaces
// the global operator new) so that the fuzz target (fuzz/fuzz_rt_loop_args.cpp) parses exactly
// what the program parses.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "fuzzypid/sim/faults.hpp"
#include "robot_options.hpp"

namespace fuzzypid::rt_loop {

inline constexpr const char* kTool = "rt_loop";
// With --csv every tick is buffered; this caps the buffer at 24 bytes x 50M = 1.2 GB.
inline constexpr std::uint64_t kMaxCsvTicks = 50'000'000;
// The range of --dt, s: the path of 5 s is sampled at dt, so 0.1 ms is 50,001 samples.
inline constexpr double kMinDtS = 1e-4;
inline constexpr double kMaxDtS = 1.0;
// The range of --period-ms, ms (0: free-running).
inline constexpr double kMaxPeriodMs = 60'000.0;

struct Options {
  double period_ms = 50.0;
  std::optional<double> dt_s;          // default: the period (50 ms when free-running)
  std::optional<std::uint64_t> ticks;  // default: one pass of the path
  std::string controller = "fuzzy";    // pid, fuzzy or a controller file (*.toml)
  std::string csv;
  std::optional<int> fifo_priority;
  bool lock_memory = false;
  std::optional<int> cpu;
  bool loop_path = false;
  bool require_rt = false;
  bool strict_rules = false;  // a tick on which the supervisor fires no rule fails the run
  // A joint whose |e| exceeds this, rad, or that leaves its URDF joint limits faults
  // (sim/faults.hpp): exit 1 unless allow_faults.
  double divergence_rad = sim::kDefaultDivergenceRad;
  bool allow_faults = false;
  std::optional<std::uint64_t> max_overruns;
  cli::RobotOptions robot;  // --urdf, --path, --tick-ms, --payload-kg, --dynamics, ...
  cli::GivenOptions given;  // for the checks that need the controller file (main)

  double controller_dt_s() const {
    if (dt_s) return *dt_s;
    return period_ms > 0.0 ? period_ms / 1000.0 : 0.05;
  }
};

// Parses the command line into `o`; nullopt to run, else the exit code (0 after --help, which it
// prints; 2 after a usage error, whose message it prints on stderr).
[[nodiscard]] std::optional<int> parse(int argc, const char* const* argv, Options& o);

}  // namespace fuzzypid::rt_loop
