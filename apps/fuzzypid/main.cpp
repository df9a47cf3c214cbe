// `fuzzypid`: command-line access to the library (fuzzy inference, robot kinematics).
#include <functional>

#include "cli.hpp"
#include "commands.hpp"
#if FUZZYPID_HAVE_MPI
#include "mpi_transport.hpp"
#endif

namespace {

int run(int argc, char** argv) {
  CLI::App app(
      "Command-line access to fuzzypid. Each command reads comma-separated rows on stdin (a "
      "header line and # comments are allowed) and writes rows with %.17g on stdout.\n"
      "Exit codes: 0 success, 1 bad input data or a failed write, 2 bad usage.",
      "fuzzypid");
  app.require_subcommand(1, 1);
  std::function<int()> run;
  fuzzypid::cli::add_eval_command(app, run);
  fuzzypid::cli::add_check_rules_command(app, run);
#if FUZZYPID_HAVE_ROBOT
  fuzzypid::cli::add_fk_command(app, run);
  fuzzypid::cli::add_ik_command(app, run);
  fuzzypid::cli::add_tune_command(app, run);
  fuzzypid::cli::add_export_header_command(app, run);
  fuzzypid::cli::add_export_rules_command(app, run);
  fuzzypid::cli::add_certify_command(app, run);
  fuzzypid::cli::add_pick_command(app, run);
  fuzzypid::cli::add_hypervolume_command(app, run);
#endif
  if (const auto code = fuzzypid::cli::parse(app, argc, argv)) return *code;
  const int code = run();
  const int written = fuzzypid::cli::finish_stdout("fuzzypid");
  return code != fuzzypid::cli::kExitOk ? code : written;
}

}  // namespace

int main(int argc, char** argv) {
  const int code = fuzzypid::cli::run_main("fuzzypid", [&] { return run(argc, argv); });
#if FUZZYPID_HAVE_MPI
  fuzzypid::cli::mpi_finish(code);
#endif
  return code;
}
