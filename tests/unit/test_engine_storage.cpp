// The model's two storage forms as a specification (issue 19 item 3): a loaded model holds exactly
// the counts of its file and occupies far less than the fixed capacity; a model of either form
// evaluates to the same bits and statuses; a fixed-capacity model is built at compile time; a
// sized model whose storage is smaller than its counts is invalid. Allocation-free evaluation of
// sized models is checked in test_engine_allocation.cpp (its own executable counts operator new).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "fuzzypid/fuzzy/engine.hpp"
#include "fuzzypid/fuzzy/engine_model_copy.hpp"
#include "fuzzypid/rulefile/rule_file.hpp"
#include "fuzzypid_support/uniform_real.hpp"

namespace {

using fuzzypid::Status;
using fuzzypid::fuzzy::DynamicWorkspace;
using fuzzypid::fuzzy::FixedCapacity;
using fuzzypid::fuzzy::model_bytes;
using fuzzypid::rulefile::Model;
using Fixed = fuzzypid::fuzzy::EngineModel<double, FixedCapacity>;

std::unique_ptr<Model> load(const std::string& path) {
  auto model = std::make_unique<Model>();
  fuzzypid::rulefile::LoadError error;
  if (!fuzzypid::rulefile::load_rule_file(path, *model, error)) {
    ADD_FAILURE() << error.to_string();
    return nullptr;
  }
  return model;
}

std::size_t workspace_bytes(const DynamicWorkspace<double>& ws) {
  std::size_t bytes = sizeof(ws);
  for (const auto* v : {&ws.membership, &ws.degree, &ws.previous, &ws.input, &ws.strength,
                        &ws.stack, &ws.level, &ws.breakpoints, &ws.lines, &ws.crossings})
    bytes += v->size() * sizeof(double);
  bytes += ws.activations.size() * sizeof(ws.activations[0]);
  bytes += (ws.order.size() + ws.heap.size()) * sizeof(std::uint32_t);
  return bytes;
}

TEST(EngineStorage, ALoadedModelHoldsExactlyTheCountsOfItsFile) {
  const auto m = load(FUZZYPID_RULEBASES_DIR "/paper.fis");
  ASSERT_TRUE(m);
  EXPECT_EQ(m->inputs.size(), 2u);
  EXPECT_EQ(m->outputs.size(), 3u);
  EXPECT_EQ(m->rules.size(), 49u);
  EXPECT_EQ(m->blocks.size(), 1u);
  EXPECT_EQ(m->tokens.size(), 49u * 3u);  // "e is A and ec is B": two propositions, one and
  EXPECT_EQ(m->conclusions.size(), 49u * 3u);
  EXPECT_EQ(m->points.size(), 0u);
  for (const auto& in : m->inputs) {
    EXPECT_EQ(in.terms.size(), 7u);
    EXPECT_EQ(in.term_names.size(), 7u);
  }
  for (const auto& out : m->outputs) {
    EXPECT_EQ(out.terms.size(), 7u);
    for (const auto& t : out.terms)  // zero-order Sugeno: one constant each
      EXPECT_EQ(t.coefficients.size(), 1u);
  }
  // Mamdani terms hold no coefficients; linear ones num_inputs + 1.
  const auto mamdani = load(FUZZYPID_RULEFILES_DIR "/mamdani_mix.fis");
  ASSERT_TRUE(mamdani);
  EXPECT_EQ(mamdani->outputs[0].terms[0].coefficients.size(), 0u);
  const auto linear = load(FUZZYPID_RULEFILES_DIR "/sugeno_linear.fll");
  ASSERT_TRUE(linear);
  std::size_t linear_terms = 0;
  for (const auto& out : linear->outputs)
    for (const auto& t : out.terms)
      if (t.kind == fuzzypid::fuzzy::OutputTermKind::Linear) {
        ++linear_terms;
        EXPECT_EQ(t.coefficients.size(), linear->num_inputs + 1);
      }
  EXPECT_GT(linear_terms, 0u);
}

TEST(EngineStorage, ModelBytesOfThePaperAndTheLargestCorpusFileAreBounded) {
  struct Case {
    const char* path;
    std::size_t max_model_bytes;
  };
  // Bounds a little above the measured bytes (docs/rule_files.md), so growth is noticed.
  const Case cases[] = {
      {FUZZYPID_RULEBASES_DIR "/paper.fis", 16'000},
      {FUZZYPID_RULEFILES_DIR "/corpus/handmade_3inputs_729rules.fis", 100'000},
  };
  for (const Case& c : cases) {
    const auto m = load(c.path);
    ASSERT_TRUE(m);
    const std::size_t model = model_bytes(*m);
    const DynamicWorkspace<double> ws(*m);
    const std::size_t workspace = workspace_bytes(ws);
    std::cout << std::filesystem::path(c.path).filename().string() << ": " << m->num_inputs
              << " inputs, " << m->num_rules << " rules; model " << model << " B (fixed capacity "
              << sizeof(Fixed) << " B), workspace " << workspace << " B\n";
    EXPECT_LE(model, c.max_model_bytes) << c.path;
    EXPECT_LT(model, sizeof(Fixed) / 4) << c.path;
  }
}

// Evaluates `model` over `samples` seeded inputs (ranges widened by 10 %) into `out`, statuses
// appended as an output.
template <class M>
std::vector<double> outputs_over(const M& model, int samples, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  DynamicWorkspace<double> ws(model);
  std::vector<double> result;
  double in[fuzzypid::fuzzy::kMaxInputs] = {};
  double out[fuzzypid::fuzzy::kMaxOutputs] = {};
  for (int n = 0; n < samples; ++n) {
    for (std::size_t i = 0; i < model.num_inputs; ++i) {
      const auto& v = model.inputs[i];
      const double lo = std::isfinite(v.min) ? v.min : -10.0;
      const double hi = std::isfinite(v.max) ? v.max : 10.0;
      const double u = fuzzypid::support::UniformReal<double>(-0.1, 1.1)(rng);
      in[i] = lo + (hi - lo) * u;
    }
    const Status s = fuzzypid::fuzzy::evaluate(model, ws.view(), in, out);
    result.insert(result.end(), out, out + model.num_outputs);
    result.push_back(static_cast<double>(s));
  }
  return result;
}

TEST(EngineStorage, SizedAndFixedFormsEvaluateToTheSameBitsOnEveryCorpusFile) {
  const std::uint64_t seed = 19;
  std::cout << "seed " << seed << "\n";
  std::vector<std::string> paths = {FUZZYPID_RULEBASES_DIR "/paper.fis",
                                    FUZZYPID_RULEBASES_DIR "/paper.fll"};
  for (const auto& e : std::filesystem::directory_iterator(FUZZYPID_RULEFILES_DIR "/corpus"))
    if (e.path().filename().string().rfind("refuse_", 0) != 0) paths.push_back(e.path().string());
  ASSERT_GT(paths.size(), 50u);
  auto fixed = std::make_unique<Fixed>();
  for (const std::string& path : paths) {
    const auto sized = load(path);
    ASSERT_TRUE(sized) << path;
    ASSERT_TRUE(fuzzypid::fuzzy::copy_model(*sized, *fixed)) << path;
    ASSERT_FALSE(fuzzypid::fuzzy::validate(*fixed)) << path;
    const std::vector<double> a = outputs_over(*sized, 300, seed);
    const std::vector<double> b = outputs_over(*fixed, 300, seed);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0) << path;
    // And back: a sized copy of the fixed model equals the loaded one, element for element.
    const auto again = fuzzypid::fuzzy::make_sized(*fixed);
    EXPECT_EQ(model_bytes(again), model_bytes(*sized)) << path;
    EXPECT_EQ(outputs_over(again, 50, seed), outputs_over(*sized, 50, seed)) << path;
  }
}

TEST(EngineStorage, ASizedModelWhoseStorageIsShorterThanItsCountsIsInvalid) {
  auto m = load(FUZZYPID_RULEBASES_DIR "/paper.fis");
  ASSERT_TRUE(m);
  ASSERT_FALSE(fuzzypid::fuzzy::validate(*m));
  m->num_rules = 50;  // one rule more than stored
  const auto e = fuzzypid::fuzzy::validate(*m);
  ASSERT_TRUE(e);
  EXPECT_STREQ(e.message, "storage smaller than the model's counts");
  Model empty;
  empty.num_inputs = 1;
  empty.num_outputs = 1;
  EXPECT_TRUE(fuzzypid::fuzzy::validate(empty)) << "a default sized model stores nothing";
}

// A fixed-capacity model is a literal type: generated headers define one as constexpr data.
constexpr fuzzypid::fuzzy::EngineModel<float, fuzzypid::fuzzy::SmallCapacity> one_rule() {
  fuzzypid::fuzzy::EngineModel<float, fuzzypid::fuzzy::SmallCapacity> m{};
  m.num_inputs = 1;
  m.num_outputs = 1;
  m.inputs[0].min = -1;
  m.inputs[0].num_terms = 1;
  m.inputs[0].terms[0] = fuzzypid::fuzzy::Term<float>::triangle(-1, 0, 1);
  m.outputs[0].defuzzifier = fuzzypid::fuzzy::Defuzzifier::WeightedAverage;
  m.outputs[0].num_terms = 1;
  m.outputs[0].terms[0].kind = fuzzypid::fuzzy::OutputTermKind::Constant;
  m.outputs[0].terms[0].coefficients[0] = 2.5f;
  m.num_rules = m.num_tokens = m.num_conclusions = 1;
  m.rules[0].num_tokens = m.rules[0].num_conclusions = 1;
  return m;
}

TEST(EngineStorage, AFixedCapacityModelIsBuiltAtCompileTime) {
  static constexpr auto m = one_rule();
  static_assert(m.num_rules == 1 && m.outputs[0].terms[0].coefficients[0] == 2.5f);
  ASSERT_FALSE(fuzzypid::fuzzy::validate(m));
  fuzzypid::fuzzy::EngineWorkspace<float, fuzzypid::fuzzy::SmallCapacity> ws;
  const float x = 0.5f;
  float y = 0;
  EXPECT_EQ(fuzzypid::fuzzy::evaluate(m, ws.view(), &x, &y), Status::Ok);
  EXPECT_EQ(y, 2.5f);
}

}  // namespace
