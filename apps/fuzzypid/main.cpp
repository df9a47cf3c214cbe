// `fuzzypid`: command-line access to the library (fuzzy inference, robot kinematics).
#include <cstdio>
#include <cstring>

#include "commands.hpp"

namespace {

void print_usage(std::FILE* out) {
  std::fputs(
      "usage: fuzzypid <command> [options]\n"
      "\n"
      "commands:\n"
      "  eval [--and min|prod]   rows e,ec on stdin -> e,ec,dKp,dKi,dKd (the paper's rule base)\n"
#if FUZZYPID_HAVE_ROBOT
      "  fk [--urdf FILE]        rows q1..q6 on stdin -> x,y,z,r11..r33 (SI units)\n"
      "  ik [--urdf FILE] [--solver analytic|kdl-nr|kdl-lma]\n"
      "                          rows x,y,z,r11..r33[,seed q1..q6] -> q1..q6,status\n"
      "  tune --family F --conditions FILE --out FILE [...]   robust tuning (docs/tuning.md)\n"
      "  export-header FILE [--out H]  a controller file as a constexpr C++ header\n"
#endif
      "\n"
      "Rows are comma-separated; a header line is allowed. Output uses %.17g.\n",
      out);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    print_usage(stderr);
    return 2;
  }
  const char* command = argv[1];
  if (std::strcmp(command, "--help") == 0 || std::strcmp(command, "-h") == 0) {
    print_usage(stdout);
    return 0;
  }
  if (std::strcmp(command, "eval") == 0) return fuzzypid::cli::run_eval(argc - 2, argv + 2);
#if FUZZYPID_HAVE_ROBOT
  if (std::strcmp(command, "fk") == 0) return fuzzypid::cli::run_fk(argc - 2, argv + 2);
  if (std::strcmp(command, "ik") == 0) return fuzzypid::cli::run_ik(argc - 2, argv + 2);
  if (std::strcmp(command, "tune") == 0) return fuzzypid::cli::run_tune(argc - 2, argv + 2);
  if (std::strcmp(command, "export-header") == 0)
    return fuzzypid::cli::run_export_header(argc - 2, argv + 2);
#endif
  std::fprintf(stderr, "fuzzypid: unknown command '%s'\n\n", command);
  print_usage(stderr);
  return 2;
}
