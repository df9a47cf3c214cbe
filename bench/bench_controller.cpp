// One full 6-joint control tick: JointController<double, 6> with a plain PID, the paper's fuzzy
// PID, the gain schedule or the fuzzy-rules table in every joint, fed from a table of references
// and measurements (the plain PID is the anchor the others are compared with in the same run).
#include <benchmark/benchmark.h>

#include <array>
#include <cstddef>

#include "bench_inputs.hpp"
#include "fuzzypid/paper.hpp"
#include "fuzzypid/pid/pid.hpp"
#include "fuzzypid/supervisor/fuzzy_pid.hpp"
#include "fuzzypid/supervisor/joint_controller.hpp"

namespace {

using fuzzypid::bench::kTableMask;
using fuzzypid::bench::kTableSize;

constexpr std::size_t kJoints = 6;
constexpr double kDt = 0.05;  // s, the paper's 50 ms tick
using fuzzypid::bench::tick_pid_config;
using fuzzypid::bench::TickInput;

// Every joint runs a copy of `joint`.
template <class Joint>
void run_ticks(benchmark::State& state, const Joint& joint) {
  fuzzypid::supervisor::JointController<double, kJoints, Joint> controller(joint);
  const auto table = fuzzypid::bench::make_tick_table();
  std::size_t k = 0;
  for (auto _ : state) {
    const TickInput& t = table[k++ & kTableMask];
    const auto cmd = controller.step(t, kDt);
    benchmark::DoNotOptimize(cmd);
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_ControllerStep6_pid(benchmark::State& state) {
  // Without the velocity observer's storage, as the paper's fuzzy PID holds its PID.
  using Pid = fuzzypid::pid::Pid<double, fuzzypid::pid::ObserverStorage::Omitted>;
  run_ticks(state, Pid(tick_pid_config()));
}
BENCHMARK(BM_ControllerStep6_pid)->Name("BM_ControllerStep6/pid");

void BM_ControllerStep6_fuzzy(benchmark::State& state) {
  using FuzzyPid = fuzzypid::paper::FuzzyPid<double>;
  auto config = fuzzypid::paper::paper_config<double>();
  config.pid = tick_pid_config();
  run_ticks(state, FuzzyPid(&fuzzypid::paper::kSystem<double>, config));
}
BENCHMARK(BM_ControllerStep6_fuzzy)->Name("BM_ControllerStep6/fuzzy");

void BM_ControllerStep6_scheduled(benchmark::State& state) {
  run_ticks(state, fuzzypid::bench::scheduled_joint());
}
BENCHMARK(BM_ControllerStep6_scheduled)->Name("BM_ControllerStep6/scheduled");

void BM_ControllerStep6_fuzzy_rules(benchmark::State& state) {
  run_ticks(state, fuzzypid::bench::fuzzy_rules_joint());
}
BENCHMARK(BM_ControllerStep6_fuzzy_rules)->Name("BM_ControllerStep6/fuzzy_rules");

}  // namespace
