// Subcommands of the `fuzzypid` command-line tool. Each registers its options on the tool's CLI11
// application and runs from the parsed options, returning the process exit code (cli.hpp: 0 ok, 1 a
// run-time failure such as a bad input row, a URDF or rule file that does not load, or a write
// error; 2 bad usage, reported by the parser before any command runs).
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

namespace fuzzypid::cli {

// Adds the subcommand to `app`; `run` is set to the function that runs it once parsed.
void add_eval_command(CLI::App& app, std::function<int()>& run);
void add_check_rules_command(CLI::App& app, std::function<int()>& run);  // check_rules.cpp

#if FUZZYPID_HAVE_ROBOT
void add_fk_command(CLI::App& app, std::function<int()>& run);
void add_ik_command(CLI::App& app, std::function<int()>& run);
void add_tune_command(CLI::App& app, std::function<int()>& run);           // tune.cpp
void add_export_header_command(CLI::App& app, std::function<int()>& run);  // tune.cpp
void add_export_rules_command(CLI::App& app, std::function<int()>& run);   // export_rules.cpp
void add_certify_command(CLI::App& app, std::function<int()>& run);        // certify.cpp
void add_pick_command(CLI::App& app, std::function<int()>& run);           // pick.cpp
void add_hypervolume_command(CLI::App& app, std::function<int()>& run);    // pick.cpp
#endif

}  // namespace fuzzypid::cli
