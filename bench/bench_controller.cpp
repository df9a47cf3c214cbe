// One full 6-joint control tick: JointController<double, 6> with a plain PID, the paper's fuzzy
// PID, the gain schedule or the fuzzy-rules table in every joint, fed from a table of references
// and measurements (the plain PID is the anchor the others are compared with in the same run).
#include <benchmark/benchmark.h>

#include <array>
#include <cstddef>

#include "bench_inputs.hpp"
#include "fuzzypid/control/fuzzy_pid.hpp"
#include "fuzzypid/control/gain_schedule.hpp"
#include "fuzzypid/control/joint_controller.hpp"
#include "fuzzypid/control/rule_table.hpp"
#include "fuzzypid/paper.hpp"
#include "fuzzypid/pid/pid.hpp"

namespace {

using fuzzypid::bench::kTableMask;
using fuzzypid::bench::kTableSize;

constexpr std::size_t kJoints = 6;
constexpr double kDt = 0.05;  // s, the paper's 50 ms tick
using fuzzypid::bench::tick_pid_config;
using fuzzypid::bench::TickInput;

template <class Controller>
void run_ticks(benchmark::State& state,
               fuzzypid::control::JointController<double, kJoints, Controller> controller) {
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
  using Pid = fuzzypid::pid::Pid<double>;
  run_ticks(state,
            fuzzypid::control::JointController<double, kJoints, Pid>(Pid(tick_pid_config())));
}
BENCHMARK(BM_ControllerStep6_pid)->Name("BM_ControllerStep6/pid");

void BM_ControllerStep6_fuzzy(benchmark::State& state) {
  using FuzzyPid = fuzzypid::paper::FuzzyPid<double>;
  auto config = fuzzypid::paper::paper_config<double>();
  config.pid = tick_pid_config();
  run_ticks(state, fuzzypid::control::JointController<double, kJoints, FuzzyPid>(
                       FuzzyPid(&fuzzypid::paper::kSystem<double>, config)));
}
BENCHMARK(BM_ControllerStep6_fuzzy)->Name("BM_ControllerStep6/fuzzy");

// The supervised families as the tuner builds them (K0 the tick PID's gains, Ke = 12, Kec = 0.7).
template <class Supervisor>
fuzzypid::control::FuzzyPidConfig<double> supervised_config(
    const std::array<double, 3>& output_scale) {
  fuzzypid::control::FuzzyPidConfig<double> c;
  c.pid = tick_pid_config();
  c.error_scale = 12.0;
  c.error_rate_scale = 0.7;
  c.output_scale = output_scale;
  return c;
}

void BM_ControllerStep6_scheduled(benchmark::State& state) {
  using Schedule = fuzzypid::control::GainSchedule<double>;
  static constexpr Schedule kSchedule{};
  const auto k0 = tick_pid_config().gains;
  using Joint = fuzzypid::control::FuzzyPid<double, Schedule>;
  run_ticks(state, fuzzypid::control::JointController<double, kJoints, Joint>(Joint(
                       &kSchedule,
                       supervised_config<Schedule>({-0.7 * k0.kp, 3.0 * k0.ki, 0.6 * k0.kd}))));
}
BENCHMARK(BM_ControllerStep6_scheduled)->Name("BM_ControllerStep6/scheduled");

void BM_ControllerStep6_fuzzy_rules(benchmark::State& state) {
  using Table = fuzzypid::control::RuleTable<double>;
  static const Table kTable = [] {
    Table t;
    t.schedule_ratio = {0.3, 4.0, 1.6};
    for (std::size_t g = 0; g < 3; ++g)
      for (std::size_t i = 0; i < Table::num_sets(); ++i)
        for (std::size_t j = 0; j < Table::num_sets(); ++j)
          t.table[g][i][j] = 1.0 + 0.05 * static_cast<double>((i * 7 + j * 3 + g) % 5);
    return t;
  }();
  const auto k0 = tick_pid_config().gains;
  using Joint = fuzzypid::control::FuzzyPid<double, Table>;
  run_ticks(state, fuzzypid::control::JointController<double, kJoints, Joint>(
                       Joint(&kTable, supervised_config<Table>({k0.kp, k0.ki, k0.kd}))));
}
BENCHMARK(BM_ControllerStep6_fuzzy_rules)->Name("BM_ControllerStep6/fuzzy_rules");

}  // namespace
