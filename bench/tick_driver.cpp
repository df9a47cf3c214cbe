// Runs N 6-joint ticks (or N inferences) on the benchmarks' own inputs, for instruction counts
// that do not depend on machine load:
//
//   valgrind --tool=callgrind --callgrind-out-file=/dev/null build/bin/fuzzypid_tick_driver fuzzy
//   1000 valgrind --tool=callgrind --callgrind-out-file=/dev/null build/bin/fuzzypid_tick_driver
//   fuzzy 101000
//
// (instructions per tick = difference of the two totals / 100,000; kinds: fuzzy, pid, scheduled,
// fuzzy_rules, infer).
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "bench_inputs.hpp"
#include "fuzzypid/paper.hpp"
#include "fuzzypid/pid/pid.hpp"

namespace {

using fuzzypid::bench::tick_pid_config;

// The tick table of bench_controller.cpp.
const auto g_table = fuzzypid::bench::make_tick_table();

template <class Controller>
[[gnu::noinline]] double run(Controller& controller, long n) {
  double sum = 0.0;
  for (long k = 0; k < n; ++k) {
    const auto out =
        controller.step(g_table[static_cast<std::size_t>(k) & fuzzypid::bench::kTableMask], 0.05);
    sum += out.torque_nm[0] + static_cast<double>(out.status);
  }
  return sum;
}

[[gnu::noinline]] double infer(long n) {
  const auto& system = fuzzypid::paper::kSystem<double>;
  auto workspace = system.make_workspace();
  const auto table = fuzzypid::bench::make_error_table();
  double sum = 0.0;
  for (long k = 0; k < n; ++k) {
    const auto& p = table[static_cast<std::size_t>(k) & fuzzypid::bench::kTableMask];
    std::array<double, 3> delta;
    const fuzzypid::Status s = system.infer(p.e, p.ec, workspace, delta);
    sum += delta[0] + delta[1] + delta[2] + static_cast<double>(s);
  }
  return sum;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3 || std::atol(argv[2]) < 1) {
    std::fprintf(stderr,
                 "usage: fuzzypid_tick_driver fuzzy|pid|scheduled|fuzzy_rules|infer COUNT\n");
    return 2;
  }
  const long n = std::atol(argv[2]);
  double sum = 0.0;
  if (std::strcmp(argv[1], "fuzzy") == 0) {
    auto config = fuzzypid::paper::paper_config<double>();
    config.pid = tick_pid_config();
    fuzzypid::paper::JointController<double, 6> controller(
        fuzzypid::paper::FuzzyPid<double>(&fuzzypid::paper::kSystem<double>, config));
    sum = run(controller, n);
  } else if (std::strcmp(argv[1], "pid") == 0) {
    fuzzypid::control::JointController<double, 6, fuzzypid::pid::Pid<double>> controller{
        fuzzypid::pid::Pid<double>(tick_pid_config())};
    sum = run(controller, n);
  } else if (std::strcmp(argv[1], "scheduled") == 0) {
    fuzzypid::control::JointController<double, 6, decltype(fuzzypid::bench::scheduled_joint())>
        controller{fuzzypid::bench::scheduled_joint()};
    sum = run(controller, n);
  } else if (std::strcmp(argv[1], "fuzzy_rules") == 0) {
    fuzzypid::control::JointController<double, 6, decltype(fuzzypid::bench::fuzzy_rules_joint())>
        controller{fuzzypid::bench::fuzzy_rules_joint()};
    sum = run(controller, n);
  } else if (std::strcmp(argv[1], "infer") == 0) {
    sum = infer(n);
  } else {
    std::fprintf(stderr,
                 "usage: fuzzypid_tick_driver fuzzy|pid|scheduled|fuzzy_rules|infer COUNT\n");
    return 2;
  }
  std::printf("%.17g\n", sum);
  return 0;
}
