// Runs N 6-joint ticks (or N inferences) on the benchmarks' own inputs, for instruction counts
// that do not depend on machine load:
//
//   valgrind --tool=callgrind --callgrind-out-file=/dev/null build/bin/fuzzypid_tick_driver fuzzy
//   1000 valgrind --tool=callgrind --callgrind-out-file=/dev/null build/bin/fuzzypid_tick_driver
//   fuzzy 101000
//
// (instructions per tick = difference of the two totals / 100,000; kinds: fuzzy, pid, scheduled,
// fuzzy_rules, infer; spec:FAMILY runs a family's default controller through the family dispatch
// of controller::JointControllers when the controller part is built).
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "bench_inputs.hpp"
#include "fuzzypid/paper.hpp"
#include "fuzzypid/pid/pid.hpp"
#ifdef FUZZYPID_TICK_DRIVER_CONTROLLERS
#include <string>

#include "fuzzypid/controller/joint_controllers.hpp"
#endif

namespace {

using fuzzypid::bench::tick_pid_config;

// The tick table of bench_controller.cpp.
const auto g_table = fuzzypid::bench::make_tick_table();

constexpr const char* kUsage =
    "usage: fuzzypid_tick_driver fuzzy|pid|scheduled|fuzzy_rules|infer|spec:FAMILY COUNT\n";

// n ticks of six joints, each a copy of `joint`.
template <class Joint>
[[gnu::noinline]] double run(const Joint& joint, long n) {
  fuzzypid::supervisor::JointController<double, 6, Joint> controller(joint);
  double sum = 0.0;
  for (long k = 0; k < n; ++k) {
    const auto out =
        controller.step(g_table[static_cast<std::size_t>(k) & fuzzypid::bench::kTableMask], 0.05);
    sum += out.output[0] + static_cast<double>(out.status);
  }
  return sum;
}

#ifdef FUZZYPID_TICK_DRIVER_CONTROLLERS
// n ticks of the six joints a controller description builds, through the family dispatch of
// controller::JointControllers (what sim/ and the apps run).
[[gnu::noinline]] double run_spec(const fuzzypid::controller::ControllerSpec& spec, long n) {
  std::string error;
  fuzzypid::controller::Vector limit;
  limit.fill(1e3);
  auto controllers = fuzzypid::controller::JointControllers::create(spec, limit, error);
  if (!controllers) {
    std::fprintf(stderr, "fuzzypid_tick_driver: %s\n", error.c_str());
    std::exit(1);
  }
  double sum = 0.0;
  for (long k = 0; k < n; ++k) {
    const auto out =
        controllers->step(g_table[static_cast<std::size_t>(k) & fuzzypid::bench::kTableMask], 0.05);
    sum += out.output[0] + static_cast<double>(out.status);
  }
  return sum;
}
#endif

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
    std::fputs(kUsage, stderr);
    return 2;
  }
  const long n = std::atol(argv[2]);
  double sum = 0.0;
  if (std::strcmp(argv[1], "fuzzy") == 0) {
    auto config = fuzzypid::paper::paper_config<double>();
    config.pid = tick_pid_config();
    sum = run(fuzzypid::paper::FuzzyPid<double>(&fuzzypid::paper::kSystem<double>, config), n);
  } else if (std::strcmp(argv[1], "pid") == 0) {
    // Without the velocity observer's storage, as the paper's fuzzy PID holds its PID.
    using Pid = fuzzypid::pid::Pid<double, fuzzypid::pid::ObserverStorage::Omitted>;
    sum = run(Pid(tick_pid_config()), n);
  } else if (std::strcmp(argv[1], "scheduled") == 0) {
    sum = run(fuzzypid::bench::scheduled_joint(), n);
  } else if (std::strcmp(argv[1], "fuzzy_rules") == 0) {
    sum = run(fuzzypid::bench::fuzzy_rules_joint(), n);
#ifdef FUZZYPID_TICK_DRIVER_CONTROLLERS
  } else if (std::strncmp(argv[1], "spec:", 5) == 0) {
    // spec:NAME: the family NAME (as controller files name it) with its default settings.
    fuzzypid::controller::ControllerSpec spec = fuzzypid::controller::paper_fuzzy();
    const auto family = fuzzypid::parse_enum(fuzzypid::controller::kFamilyNames, argv[1] + 5);
    if (!family) {
      std::fputs(kUsage, stderr);
      return 2;
    }
    spec.family = *family;
    sum = run_spec(spec, n);
#endif
  } else if (std::strcmp(argv[1], "infer") == 0) {
    sum = infer(n);
  } else {
    std::fputs(kUsage, stderr);
    return 2;
  }
  std::printf("%.17g\n", sum);
  return 0;
}
