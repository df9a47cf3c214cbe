// One full 6-joint control tick: JointController<double, 6> with a plain PID or the paper's fuzzy
// PID in every joint, fed from a table of references and measurements.
#include <benchmark/benchmark.h>

#include <array>
#include <cstddef>

#include "bench_inputs.hpp"
#include "fuzzypid/control/fuzzy_pid.hpp"
#include "fuzzypid/control/joint_controller.hpp"
#include "fuzzypid/paper.hpp"
#include "fuzzypid/pid/pid.hpp"

namespace {

using fuzzypid::bench::kTableMask;
using fuzzypid::bench::kTableSize;

constexpr std::size_t kJoints = 6;
constexpr double kDt = 0.05;  // s, the paper's 50 ms tick
using TickInput = fuzzypid::control::JointInput<double, kJoints>;

// Tracking errors of up to +-0.35 rad and +-0.35 rad/s around a moving reference: the fuzzy
// supervisor sees inputs across its whole universe and slightly outside it.
std::array<TickInput, kTableSize> make_tick_table() {
  std::array<TickInput, kTableSize> table{};
  fuzzypid::bench::SplitMix64 rng(7);
  for (auto& t : table) {
    for (std::size_t j = 0; j < kJoints; ++j) {
      t.desired_position_rad[j] = rng.uniform(-1.5, 1.5);
      t.desired_velocity_rad_s[j] = rng.uniform(-0.5, 0.5);
      t.measured_position_rad[j] = t.desired_position_rad[j] + rng.uniform(-0.35, 0.35);
      t.measured_velocity_rad_s[j] = t.desired_velocity_rad_s[j] + rng.uniform(-0.35, 0.35);
    }
  }
  return table;
}

// The paper's gains (section 5.2) with the derivative taken from the measured rates (Eq. 2).
fuzzypid::pid::Config<double> pid_config() {
  fuzzypid::pid::Config<double> c;
  c.gains = fuzzypid::paper::kNominalGains<double>;
  c.derivative_source = fuzzypid::pid::DerivativeSource::Rates;
  return c;
}

template <class Controller>
void run_ticks(benchmark::State& state,
               fuzzypid::control::JointController<double, kJoints, Controller> controller) {
  const auto table = make_tick_table();
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
  run_ticks(state, fuzzypid::control::JointController<double, kJoints, Pid>(Pid(pid_config())));
}
BENCHMARK(BM_ControllerStep6_pid)->Name("BM_ControllerStep6/pid");

void BM_ControllerStep6_fuzzy(benchmark::State& state) {
  using FuzzyPid = fuzzypid::paper::FuzzyPid<double>;
  auto config = fuzzypid::paper::paper_config<double>();
  config.pid = pid_config();
  run_ticks(state, fuzzypid::control::JointController<double, kJoints, FuzzyPid>(
                       FuzzyPid(&fuzzypid::paper::kSystem<double>, config)));
}
BENCHMARK(BM_ControllerStep6_fuzzy)->Name("BM_ControllerStep6/fuzzy");

}  // namespace
