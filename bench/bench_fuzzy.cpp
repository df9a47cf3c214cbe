// One inference of the paper's fuzzy supervisor (e, ec -> dKp, dKi, dKd): fuzzypid's table
// system against the same system built in fuzzylite 6, on the same inputs in the same binary.
#include <benchmark/benchmark.h>
#include <fl/Headers.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <memory>
#include <string>

#include "bench_inputs.hpp"
#include "fuzzypid/paper.hpp"

namespace {

using fuzzypid::bench::kTableMask;
using fuzzypid::bench::make_error_table;

constexpr std::size_t kTerms = fuzzypid::paper::kNumTerms;

// The paper's system in fuzzylite: zero-order Takagi-Sugeno, one Constant term per table cell,
// weighted-average defuzzification, no aggregation, minimum conjunction. The outer terms are
// open trapezoids, the fuzzylite spelling of the core's shoulders, so both saturate alike outside
// [-0.3, 0.3].
std::unique_ptr<fl::Engine> make_fuzzylite_engine() {
  auto engine = std::make_unique<fl::Engine>("paper");
  const char* const names[2] = {"e", "ec"};
  for (const char* name : names) {
    auto* in = new fl::InputVariable(name, -0.3, 0.3);
    const std::array<double, kTerms> peaks = fuzzypid::paper::kSystem<double>.e.centers();
    in->addTerm(
        new fl::Trapezoid(fuzzypid::paper::kTermNames[0], -fl::inf, -fl::inf, peaks[0], peaks[1]));
    for (std::size_t k = 1; k + 1 < kTerms; ++k)
      in->addTerm(
          new fl::Triangle(fuzzypid::paper::kTermNames[k], peaks[k - 1], peaks[k], peaks[k + 1]));
    in->addTerm(new fl::Trapezoid(fuzzypid::paper::kTermNames[kTerms - 1], peaks[kTerms - 2],
                                  peaks[kTerms - 1], fl::inf, fl::inf));
    engine->addInputVariable(in);
  }
  const fuzzypid::paper::Table* tables[3] = {&fuzzypid::paper::kDeltaKpPrinted,
                                             &fuzzypid::paper::kDeltaKiPrinted,
                                             &fuzzypid::paper::kDeltaKdPrinted};
  const char* const outputs[3] = {"dKp", "dKi", "dKd"};
  for (std::size_t o = 0; o < 3; ++o) {
    auto* out = new fl::OutputVariable(outputs[o], -1.0, 1.0);
    out->setDefuzzifier(new fl::WeightedAverage(fl::WeightedAverage::TakagiSugeno));
    out->setAggregation(fl::null);
    out->setDefaultValue(fl::nan);
    for (std::size_t i = 0; i < kTerms; ++i)
      for (std::size_t j = 0; j < kTerms; ++j)
        out->addTerm(
            new fl::Constant("c" + std::to_string(i) + std::to_string(j), (*tables[o])[i][j]));
    engine->addOutputVariable(out);
  }
  auto* rules = new fl::RuleBlock("tables_2_4");
  rules->setConjunction(new fl::Minimum);
  rules->setDisjunction(fl::null);
  rules->setImplication(fl::null);
  rules->setActivation(new fl::General);
  for (std::size_t i = 0; i < kTerms; ++i) {
    for (std::size_t j = 0; j < kTerms; ++j) {
      const std::string cell = "c" + std::to_string(i) + std::to_string(j);
      rules->addRule(fl::Rule::parse(std::string("if e is ") + fuzzypid::paper::kTermNames[i] +
                                         " and ec is " + fuzzypid::paper::kTermNames[j] +
                                         " then dKp is " + cell + " and dKi is " + cell +
                                         " and dKd is " + cell,
                                     engine.get()));
    }
  }
  engine->addRuleBlock(rules);
  return engine;
}

// Largest |fuzzypid - fuzzylite| over the input table, every output. fuzzylite compares with a
// tolerance of 1e-6 by default; it is set to 0 here so the two are the same function.
double max_difference(fl::Engine& engine) {
  const auto& system = fuzzypid::paper::kSystem<double>;
  const auto table = make_error_table();
  double worst = 0.0;
  for (const auto& p : table) {
    engine.getInputVariable(0)->setValue(p.e);
    engine.getInputVariable(1)->setValue(p.ec);
    engine.process();
    const auto r = system.infer(p.e, p.ec);
    for (std::size_t o = 0; o < 3; ++o) {
      const double d = std::fabs(r.output[o] - engine.getOutputVariable(o)->getValue());
      if (!(d <= worst)) worst = d;  // NaN propagates as the worst difference
    }
  }
  return worst;
}

using PaperSystem = fuzzypid::paper::System<double>;

// One inference of the paper's system per iteration, over the varied input table: the
// supervisor form FuzzyPid calls every tick (WithTrace false) or the same inference with its trace
// of degrees and total strength (WithTrace true).
template <bool WithTrace>
void run_inference(benchmark::State& state) {
  const PaperSystem& system = fuzzypid::paper::kSystem<double>;
  auto workspace = system.make_workspace();
  const auto table = make_error_table();
  std::size_t k = 0;
  for (auto _ : state) {
    const auto& p = table[k++ & kTableMask];
    std::array<double, 3> delta;
    if constexpr (WithTrace) {
      PaperSystem::Trace trace;
      const fuzzypid::Status s = system.infer(p.e, p.ec, workspace, delta, trace);
      benchmark::DoNotOptimize(s);
      benchmark::DoNotOptimize(trace);
    } else {
      const fuzzypid::Status s = system.infer(p.e, p.ec, workspace, delta);
      benchmark::DoNotOptimize(s);
    }
    benchmark::DoNotOptimize(delta);
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_FuzzyInference(benchmark::State& state) {
  run_inference<false>(state);
}
BENCHMARK(BM_FuzzyInference)->Name("BM_FuzzyInference/paper");

void BM_FuzzyInferenceTraced(benchmark::State& state) {
  run_inference<true>(state);
}
BENCHMARK(BM_FuzzyInferenceTraced)->Name("BM_FuzzyInference/paper_traced");

void BM_Fuzzylite(benchmark::State& state) {
  fl::fuzzylite::setMachEps(0.0);
  auto engine = make_fuzzylite_engine();
  const double diff = max_difference(*engine);
  if (!(diff <= 1e-12)) {
    state.SkipWithError("fuzzylite and fuzzypid disagree on the paper's system");
    return;
  }
  fl::InputVariable* e = engine->getInputVariable(0);
  fl::InputVariable* ec = engine->getInputVariable(1);
  fl::OutputVariable* outs[3] = {engine->getOutputVariable(0), engine->getOutputVariable(1),
                                 engine->getOutputVariable(2)};
  const auto table = make_error_table();
  std::size_t k = 0;
  for (auto _ : state) {
    const auto& p = table[k++ & kTableMask];
    e->setValue(p.e);
    ec->setValue(p.ec);
    engine->process();
    std::array<double, 3> y{outs[0]->getValue(), outs[1]->getValue(), outs[2]->getValue()};
    benchmark::DoNotOptimize(y);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["max_abs_diff"] = diff;
}
BENCHMARK(BM_Fuzzylite)->Name("BM_Fuzzylite/paper");

}  // namespace
