// Subcommands of the `fuzzypid` command-line tool. Each takes the arguments after its own name
// and returns the process exit code (0 on success, 1 on bad input, 2 on bad usage).
#pragma once

namespace fuzzypid::cli {

int run_eval(int argc, char** argv);

#if FUZZYPID_HAVE_ROBOT
int run_fk(int argc, char** argv);
int run_ik(int argc, char** argv);
int run_tune(int argc, char** argv);           // tune.cpp
int run_export_header(int argc, char** argv);  // tune.cpp
#endif

}  // namespace fuzzypid::cli
