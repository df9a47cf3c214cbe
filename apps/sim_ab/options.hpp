// sim_ab's command line (CLI11): what to run (scenarios, conditions, condition sets, controller
// files, a robustness sweep) and the paper's modelling choices. Kept apart from main() so that the
// fuzz target (fuzz/fuzz_sim_ab_args.cpp) parses exactly what the program parses.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fuzzypid/sim/condition.hpp"
#include "fuzzypid/sim/experiment.hpp"
#include "fuzzypid/sim/sweep.hpp"
#include "robot_options.hpp"

namespace fuzzypid::sim_ab {

struct Options {
  std::string scenario = "paper";        // a named scenario or "all"
  std::string conditions_file;           // --conditions FILE
  std::vector<std::string> sets;         // --set NAME (default: every set of the file)
  std::vector<std::string> controllers;  // --controller FILE (default: the paper's pid, fuzzy)
  std::optional<sim::Sweep> sweep;       // --sweep PARAMETER=LO:HI:N
  double overshoot_bound_pct = 20.0;     // usable range of a sweep
  double itae_ratio_bound = 3.0;         // usable range: ITAE <= ratio x the nominal ITAE
  std::string out_dir = "out";
  cli::RobotOptions robot;  // --urdf, --path, --tick-ms, --payload-kg, --dynamics, ...
  std::optional<Eigen::Vector3d> start_mm, end_mm;
  sim::ExperimentOptions experiment{};
  // Overrides applied to the conditions selected by --scenario.
  std::optional<double> payload_scale, friction, torque_limit, contact, initial_error;
  std::optional<std::array<double, 2>> noise;
  std::optional<std::uint64_t> seed;
  bool reverse = false;
  bool strict_rules = false;  // a tick on which a supervisor fires no rule fails the run
  // A joint whose |e| exceeds this, rad, faults (sim/faults.hpp); so does one that leaves its
  // URDF joint limits. A run with faults exits 1 unless allow_faults.
  double divergence_rad = sim::kDefaultDivergenceRad;
  bool allow_faults = false;
  bool list = false;
  bool quiet = false;
  cli::GivenOptions given;  // for the checks that need the controllers and conditions (main)
};

enum class ParseResult { Run, Exit, UsageError };

// Parses argv. Prints --help (Exit) or the usage error (UsageError, exit code 2) itself.
[[nodiscard]] ParseResult parse(int argc, const char* const* argv, Options& options);

// The conditions selected by --scenario and the overrides (not --conditions).
[[nodiscard]] std::vector<sim::Condition> scenario_conditions(const Options& options);

}  // namespace fuzzypid::sim_ab
