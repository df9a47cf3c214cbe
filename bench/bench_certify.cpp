// The cost of the frozen-gain margins (sim/margins.hpp) and of `fuzzypid certify` on the ER50's
// default condition (sim/certify.hpp) per shipped controller.
#include <benchmark/benchmark.h>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid/sim/certify.hpp"
#include "fuzzypid/sim/experiment.hpp"
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

}  // namespace
