// The cost of the frozen-gain margins (sim/margins.hpp), of the common-Lyapunov certificate
// (sim/lyapunov.hpp) and of `fuzzypid certify` (sim/certify.hpp) per shipped controller on the
// ER50's default condition, and of the tuned PID over the drive plant's 19 held-out conditions.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid/sim/certify.hpp"
#include "fuzzypid/sim/condition_set.hpp"
#include "fuzzypid/sim/experiment.hpp"
#include "fuzzypid/sim/lyapunov.hpp"
#include "fuzzypid/sim/margins.hpp"

namespace {

// One margins() of a PID loop, the plant gain varied over 256 values (0.5 .. 2 of nominal).
void BM_Margins(benchmark::State& state) {
  std::array<double, 256> gain{};
  for (std::size_t k = 0; k < gain.size(); ++k)
    gain[k] = 0.5 + 1.5 * static_cast<double>(k) / static_cast<double>(gain.size() - 1);
  fuzzypid::sim::JointLoop loop;
  loop.tick_s = 0.05;
  loop.gains = {172.5, 0.00045, 21.35};
  std::size_t k = 0;
  for (auto _ : state) {
    loop.plant_gain = gain[k++ % gain.size()];
    benchmark::DoNotOptimize(fuzzypid::sim::margins(loop));
  }
}
BENCHMARK(BM_Margins)->Unit(benchmark::kMicrosecond);

// The same loop with a 30 Hz current loop (a third plant state, the matrix exponential).
void BM_MarginsCurrentLoop(benchmark::State& state) {
  fuzzypid::sim::JointLoop loop;
  loop.tick_s = 0.05;
  loop.gains = {172.5, 0.00045, 21.35};
  loop.torque_bandwidth_hz = 30.0;
  std::size_t k = 0;
  for (auto _ : state) {
    loop.plant_gain = 0.5 + 1.5 * static_cast<double>(k++ % 256) / 255.0;
    benchmark::DoNotOptimize(fuzzypid::sim::margins(loop));
  }
}
BENCHMARK(BM_MarginsCurrentLoop)->Unit(benchmark::kMicrosecond);

// One certificate: a PID box (8 corners) at 10 ms with the plant gain in a factor-2 range, with
// (arg 1) or without (arg 0) a tick of delay and a 50 Hz current loop.
void BM_CommonLyapunov(benchmark::State& state) {
  fuzzypid::sim::SwitchingLoop s;
  s.loop.tick_s = 0.01;
  s.gains.low = {20.0, 2.0, 6.0};
  s.gains.high = {40.0, 8.0, 10.0};
  s.plant_gain_min = 0.7;
  s.plant_gain_max = 1.4;
  if (state.range(0) != 0) {
    s.loop.delay_ticks = 1;
    s.loop.derivative_filter_s = 0.005;
    s.torque_bandwidth_min_hz = s.torque_bandwidth_max_hz = 50.0;
  }
  for (auto _ : state) {
    const auto c = fuzzypid::sim::common_lyapunov(s);
    if (!c.certified) state.SkipWithError(c.reason.c_str());
    benchmark::DoNotOptimize(c);
  }
}
BENCHMARK(BM_CommonLyapunov)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// One certify() as the CLI runs it (default grid), the experiment built once outside the loop.
void BM_Certify(benchmark::State& state, const char* file) {
  fuzzypid::controller::ControllerSpec spec;
  fuzzypid::FileError err;
  if (!fuzzypid::controller_file::load(std::string(FUZZYPID_SOURCE_DIR) + "/" + file, spec, err)) {
    state.SkipWithError(err.to_string().c_str());
    return;
  }
  const std::vector<fuzzypid::sim::Condition> conditions{fuzzypid::sim::Condition{}};
  std::string error;
  const auto experiments =
      fuzzypid::sim::ExperimentSet::create(conditions, fuzzypid::sim::ExperimentOptions{}, error);
  if (!experiments) {
    state.SkipWithError(error.c_str());
    return;
  }
  for (auto _ : state) {
    auto cert = fuzzypid::sim::certify(spec, conditions, *experiments, {}, error);
    if (!cert) state.SkipWithError(error.c_str());
    benchmark::DoNotOptimize(cert);
  }
}
BENCHMARK_CAPTURE(BM_Certify, paper_pid, "controllers/paper_pid.toml")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Certify, tuned_pid, "controllers/tuned_pid.toml")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Certify, tuned_scheduled, "controllers/tuned_scheduled.toml")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Certify, tuned_fuzzy, "controllers/tuned_fuzzy.toml")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Certify, tuned_fuzzy_rules, "controllers/tuned_fuzzy_rules.toml")
    ->Unit(benchmark::kMillisecond);

// certify over tuning/robust_drive.toml's held-out set (19 conditions with delay, current loops,
// payloads) as `fuzzypid certify --conditions ... --set held-out` runs it.
void BM_CertifyDriveHeldOut(benchmark::State& state, const char* file) {
  fuzzypid::controller::ControllerSpec spec;
  fuzzypid::FileError err;
  fuzzypid::sim::ConditionFile conditions;
  if (!fuzzypid::controller_file::load(std::string(FUZZYPID_SOURCE_DIR) + "/" + file, spec, err) ||
      !fuzzypid::sim::load_conditions(
          std::string(FUZZYPID_SOURCE_DIR) + "/tuning/robust_drive.toml", conditions, err)) {
    state.SkipWithError(err.to_string().c_str());
    return;
  }
  const auto& set = conditions.find("held-out")->conditions;
  std::string error;
  const auto experiments =
      fuzzypid::sim::ExperimentSet::create(set, fuzzypid::sim::ExperimentOptions{}, error);
  if (!experiments) {
    state.SkipWithError(error.c_str());
    return;
  }
  fuzzypid::sim::CertifyOptions options;
  for (const auto& c : set)
    options.delay_s = std::max(options.delay_s, c.effects.delay_s);
  for (auto _ : state) {
    auto cert = fuzzypid::sim::certify(spec, set, *experiments, options, error);
    if (!cert) state.SkipWithError(error.c_str());
    benchmark::DoNotOptimize(cert);
  }
}
BENCHMARK_CAPTURE(BM_CertifyDriveHeldOut, tuned_pid, "controllers/tuned_pid.toml")
    ->Unit(benchmark::kMillisecond);

}  // namespace
