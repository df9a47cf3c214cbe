// A loaded rule base evaluates without allocating: the global allocation functions are replaced
// by counting ones (so this file is its own executable), files are loaded first (loading may
// allocate), then the counter must not move over 100,000 evaluations of each system and 100,000
// FuzzyPid ticks driven by the loaded paper system.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdlib>
#include <memory>
#include <new>
#include <string>

#include "fuzzypid/fuzzy/engine.hpp"
#include "fuzzypid/paper.hpp"
#include "fuzzypid/rulefile/rule_file.hpp"
#include "fuzzypid/supervisor/engine_supervisor.hpp"
#include "fuzzypid/supervisor/fuzzy_pid.hpp"
#include "fuzzypid_support/counting_new.hpp"

namespace {

using fuzzypid::rulefile::LoadError;
using fuzzypid::rulefile::LoadOptions;
using fuzzypid::rulefile::Model;
using fuzzypid::support::allocation_count;

std::unique_ptr<Model> load(const std::string& path, const LoadOptions& options = {}) {
  auto model = std::make_unique<Model>();
  LoadError error;
  EXPECT_TRUE(fuzzypid::rulefile::load_rule_file(path, *model, error, options))
      << error.to_string();
  return model;
}

TEST(EngineAllocation, EvaluationAllocatesNothingAfterLoad) {
  LoadOptions exact;
  exact.exact_centroid = true;
  const std::unique_ptr<Model> models[] = {
      load(FUZZYPID_RULEBASES_DIR "/paper.fis"), load(FUZZYPID_RULEBASES_DIR "/paper.fll"),
      load(FUZZYPID_RULEFILES_DIR "/mamdani_mix.fis"),
      load(FUZZYPID_RULEFILES_DIR "/mamdani_mix.fis", exact),
      load(FUZZYPID_RULEFILES_DIR "/mamdani_ops.fll"),
      load(FUZZYPID_RULEFILES_DIR "/sugeno_linear.fll"),
      // chained outputs; lock-previous in the workspace
      load(FUZZYPID_RULEFILES_DIR "/corpus/chained_dimmer_two_blocks.fll"),
      load(FUZZYPID_RULEFILES_DIR "/corpus/handmade_lock_previous_heater.fll"),
      // formulas (Function terms) of inputs and of Takagi-Sugeno outputs
      load(FUZZYPID_RULEFILES_DIR "/corpus/fuzzylite8_function_input_terms.fll"),
      load(FUZZYPID_RULEFILES_DIR "/corpus/fuzzylite8_function_operators.fll"),
      // the largest corpus file (729 rules), sized to its counts
      load(FUZZYPID_RULEFILES_DIR "/corpus/handmade_3inputs_729rules.fis")};
  for (const auto& model : models) {
    ASSERT_TRUE(model);
    auto engine = std::make_unique<fuzzypid::fuzzy::Engine<double>>(*model);
    double in[fuzzypid::fuzzy::kMaxInputs] = {};
    double out[fuzzypid::fuzzy::kMaxOutputs] = {};
    const std::size_t before = allocation_count();
    double checksum = 0.0;
    for (int n = 0; n < 100000; ++n) {
      for (std::size_t i = 0; i < model->num_inputs; ++i) {
        const auto& v = model->inputs[i];
        in[i] = v.min + (v.max - v.min) * static_cast<double>((n * 7919 + 13 * i) % 1000) / 999.0;
      }
      (void)engine->evaluate(in, out);
      checksum += out[0];
    }
    EXPECT_EQ(allocation_count(), before) << "allocations in 100,000 evaluations";
    EXPECT_TRUE(checksum == checksum);
  }
}

TEST(EngineAllocation, FuzzyPidWithALoadedSystemAllocatesNothingPerTick) {
  const auto model = load(FUZZYPID_RULEBASES_DIR "/paper.fis");
  using Supervisor = fuzzypid::supervisor::EngineSupervisor<double>;
  const Supervisor supervisor(model.get());
  auto controller = std::make_unique<fuzzypid::supervisor::FuzzyPid<double, Supervisor>>(
      &supervisor, fuzzypid::paper::paper_config<double>());
  const std::size_t before = allocation_count();
  fuzzypid::pid::Input<double> in;
  in.setpoint = 0.1;
  for (int n = 0; n < 100000; ++n) {
    in.measurement = 0.1 * static_cast<double>(n % 100) / 100.0;
    (void)controller->update(in, 0.001);
  }
  EXPECT_EQ(allocation_count(), before);
}

}  // namespace
