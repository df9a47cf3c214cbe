// A 6-joint fuzzy PID whose supervisor is a rule file, in float, closed around the simulated plant
// of harness.hpp, on a Cortex-M4F (QEMU mps2-an386, semihosting) or on the host. The controller
// comes from a header written by export-header for tests/sim/data/engine_fuzzy.toml (the paper's
// rules read from rulebases/paper.fll): the rule base written out as straight-line code, so the
// target holds no parser, no interpreter and no heap. Prints what main.cpp prints for its fuzzy
// controller: one line of six command bits per tick, then '#' summary lines (on the Cortex-M4F
// with the instructions per 6-joint tick).
//
// usage: rule_file_main [ticks] [print|quiet]   (default 10000 print)
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "engine_fuzzy.hpp"  // generated: namespace engine_fuzzy
#include "fuzzypid/supervisor/joint_controller.hpp"
#include "harness.hpp"

using namespace cortex_m4_example;

int main(int argc, char** argv) {
  const long ticks = argc > 1 ? std::strtol(argv[1], nullptr, 10) : 10000;
  const char* const mode = argc > 2 ? argv[2] : "print";
  const bool print = std::strcmp(mode, "print") == 0;
  if (ticks < 1 || (!print && std::strcmp(mode, "quiet") != 0)) {
    std::fprintf(stderr, "usage: rule_file_main [ticks >= 1] [print|quiet]\n");
    return 2;
  }
  start_systick();

  fuzzypid::supervisor::JointController<float, kJoints, engine_fuzzy::Controller<float>> fuzzy(
      engine_fuzzy::make_controller<float>(50.0f));
  fuzzypid::Status worst = fuzzypid::Status::Ok;
  const std::uint64_t counts = run(fuzzy, ticks, print, worst);
  const std::uint64_t empty_counts = overhead(ticks);

  std::printf("# ticks %ld\n", ticks);
  std::printf("# rule-file fuzzy status %s\n", fuzzypid::to_string(worst));
#if defined(__ARM_ARCH_7EM__)
  // Instructions per tick, x100, net of the two SysTick reads (integer arithmetic).
  const std::uint64_t net = counts > empty_counts ? counts - empty_counts : 0;
  const auto x100 = static_cast<unsigned long>(net * kInstructionsPerCount * 100 /
                                               static_cast<std::uint64_t>(ticks));
  std::printf("# instructions per 6-joint rule-file tick %lu.%02lu\n", x100 / 100, x100 % 100);
#else
  (void)counts;
  (void)empty_counts;
#endif
  return fuzzypid::is_fault(worst) ? 1 : 0;
}
