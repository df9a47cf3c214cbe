// The paper's 6-joint fuzzy PID in float, closed around a simulated plant, on a Cortex-M4F (QEMU
// mps2-an386, semihosting) or on the host. Both builds print the same lines when both are
// compiled with -ffp-contract=off: one line per tick with the six commands' IEEE-754 bits in hex,
// then summary lines starting with '#'. On the Cortex-M4F the summary also gives the instructions
// per tick counted with SysTick under `qemu-system-arm -icount shift=0` (one instruction per
// nanosecond, SysTick at the board's 25 MHz: one count is 40 instructions).
//
// usage: main [ticks] [print|quiet|fuzzy]   (default 10000 print; "quiet" prints only the summary,
//        "fuzzy" runs only the fuzzy controller's loop, for an instruction trace)
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "fuzzypid/fuzzypid.hpp"  // the whole core compiles for the Cortex-M4F (-Werror)
#include "harness.hpp"

using namespace cortex_m4_example;

int main(int argc, char** argv) {
  const long ticks = argc > 1 ? std::strtol(argv[1], nullptr, 10) : 10000;
  const char* const mode = argc > 2 ? argv[2] : "print";
  const bool print = std::strcmp(mode, "print") == 0;
  const bool fuzzy_only = std::strcmp(mode, "fuzzy") == 0;
  if (ticks < 1 || (!print && !fuzzy_only && std::strcmp(mode, "quiet") != 0)) {
    std::fprintf(stderr, "usage: main [ticks >= 1] [print|quiet|fuzzy]\n");
    return 2;
  }
  start_systick();

  // The paper's configuration with a torque limit; its rule base is constexpr data in flash.
  auto config = fuzzypid::paper::paper_config<float>();
  config.pid.output_min = -50.0f;
  config.pid.output_max = 50.0f;
  fuzzypid::paper::JointController<float, kJoints> fuzzy(
      fuzzypid::paper::FuzzyPid<float>(&fuzzypid::paper::kSystem<float>, config));
  // The fixed PID as the paper's fuzzy PID holds it: without the velocity observer's storage.
  using FixedPid = fuzzypid::pid::Pid<float, fuzzypid::pid::ObserverStorage::Omitted>;
  fuzzypid::supervisor::JointController<float, kJoints, FixedPid> fixed(FixedPid(config.pid));

  fuzzypid::Status worst_fuzzy = fuzzypid::Status::Ok;
  fuzzypid::Status worst_pid = fuzzypid::Status::Ok;
  const std::uint64_t fuzzy_counts = run(fuzzy, ticks, print, worst_fuzzy);
  if (fuzzy_only) return fuzzypid::is_fault(worst_fuzzy) ? 1 : 0;
  const std::uint64_t pid_counts = run(fixed, ticks, false, worst_pid);
  const std::uint64_t empty_counts = overhead(ticks);

  std::printf("# ticks %ld\n", ticks);
  std::printf("# fuzzy status %s, pid status %s\n", fuzzypid::to_string(worst_fuzzy),
              fuzzypid::to_string(worst_pid));
#if defined(__ARM_ARCH_7EM__)
  // Instructions per tick, x100, net of the two SysTick reads (integer arithmetic: no float
  // formatting needed from newlib).
  const auto per_tick_x100 = [&](std::uint64_t counts) {
    const std::uint64_t net = counts > empty_counts ? counts - empty_counts : 0;
    return static_cast<unsigned long>(net * kInstructionsPerCount * 100 /
                                      static_cast<std::uint64_t>(ticks));
  };
  const unsigned long fuzzy_x100 = per_tick_x100(fuzzy_counts);
  const unsigned long pid_x100 = per_tick_x100(pid_counts);
  std::printf("# instructions per 6-joint fuzzy tick %lu.%02lu\n", fuzzy_x100 / 100,
              fuzzy_x100 % 100);
  std::printf("# instructions per 6-joint pid tick %lu.%02lu\n", pid_x100 / 100, pid_x100 % 100);
#else
  (void)fuzzy_counts;
  (void)pid_counts;
  (void)empty_counts;
#endif
  return fuzzypid::is_fault(worst_fuzzy) || fuzzypid::is_fault(worst_pid) ? 1 : 0;
}
