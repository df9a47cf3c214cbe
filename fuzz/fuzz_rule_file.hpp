// Shared body of the rule-file fuzz targets: parse arbitrary bytes; when they load, the model must
// export, re-import to an engine with identical outputs, and evaluate without sanitizer reports.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>

#include "fuzzypid/fuzzy/engine.hpp"
#include "fuzzypid/rulefile/rule_file.hpp"
#include "fuzzypid/supervisor/engine_supervisor.hpp"

namespace fuzzypid::fuzz {

using Parser = bool (*)(std::string_view, const std::string&, rulefile::Model&,
                        rulefile::LoadError&, const rulefile::LoadOptions&);

inline void check_engine(const rulefile::Model& model) {
  fuzzy::DynamicWorkspace<double> ws(model);
  double in[fuzzy::kMaxInputs] = {};
  double out[fuzzy::kMaxOutputs] = {};
  for (int k = 0; k < 4; ++k) {
    for (std::size_t i = 0; i < model.num_inputs; ++i) {
      const auto& v = model.inputs[i];
      const double lo = v.min > -1e300 ? v.min : -1.0, hi = v.max < 1e300 ? v.max : 1.0;
      in[i] = lo + (hi - lo) * (k - 0.5) / 2.0;
    }
    (void)fuzzy::evaluate(model, ws.view(), in, out);
  }
}

inline int run(const std::uint8_t* data, std::size_t size, Parser parse) {
  // Cap the resolution so a fuzzed "Centroid 100000000" cannot stall the run.
  if (size > 1 << 16) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto model = std::make_unique<rulefile::Model>();
  rulefile::LoadError error;
  rulefile::LoadOptions options;
  if (!parse(text, "fuzz", *model, error, options)) {
    if (error.message.empty()) std::abort();  // every failure must say why
    return 0;
  }
  for (std::size_t o = 0; o < model->num_outputs; ++o)
    if (model->outputs[o].resolution > 10000) return 0;
  check_engine(*model);
  std::string fll, why;
  auto again = std::make_unique<rulefile::Model>();
  if (!rulefile::to_fll(*model, fll, why)) {
    // Every loaded model is expressible in .fll but a .fis that means what Octave computes or a
    // Tsukamoto .fis read per activation (fuzzylite 6) that concludes a term twice.
    if (why.find("Octave's") == std::string::npos &&
        why.find("a .fis read as fuzzylite 6 reads it") == std::string::npos)
      std::abort();
  } else if (!rulefile::parse_fll(fll, "export", *again, error, options)) {
    std::abort();
  }
  std::string fis, fcl;
  if (rulefile::to_fis(*model, fis, why) &&
      !rulefile::parse_fis(fis, "export", *again, error, options))
    std::abort();
  if (rulefile::to_fcl(*model, fcl, why) &&
      !rulefile::parse_fcl(fcl, "export", *again, error, options))
    std::abort();
  return 0;
}

}  // namespace fuzzypid::fuzz
