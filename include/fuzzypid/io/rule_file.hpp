// Loading and saving rule bases as MATLAB Fuzzy Logic Toolbox `.fis` and fuzzylite `.fll` files
// (library fuzzypid::rulefile; see docs/rule_files.md for the supported subset).
//
// Loading allocates and parses text; it happens once, outside the control loop. What the engine
// cannot represent exactly is rejected with the file, line and offending item -- never
// approximated. The loaded fuzzy::EngineModel<double> then runs allocation-free through
// fuzzy::Engine or, for FuzzyPid, fuzzy::EngineSupervisor.
#pragma once

#include <string>
#include <string_view>

#include "fuzzypid/fuzzy/engine.hpp"

namespace fuzzypid::io {

using Model = fuzzy::EngineModel<double>;

struct LoadError {
  std::string file;     // the path or source name given to the loader
  int line = 0;         // 1-based; 0 when the problem concerns the whole file
  std::string message;  // what is wrong, naming the unsupported or malformed item

  // "file:line: message" (or "file: message" when line is 0).
  std::string to_string() const;
};

struct LoadOptions {
  // Samples of the integral defuzzifiers for .fis files, which do not state one (fuzzylite's
  // FisImporter uses 100; MATLAB samples 101 points including both ends -- see the docs).
  int fis_resolution = 100;
  // Compute Centroid in closed form instead of sampling (all output terms must be piecewise
  // linear, or loading fails). Not stored in the files.
  bool exact_centroid = false;
};

// Parse `text` as the named format; `source` names it in errors. On failure `model` is left in an
// unspecified state and `error` says why. The model is large (~45 kB): keep it on the heap.
[[nodiscard]] bool parse_fll(std::string_view text, const std::string& source, Model& model,
                             LoadError& error, const LoadOptions& options = {});
[[nodiscard]] bool parse_fis(std::string_view text, const std::string& source, Model& model,
                             LoadError& error, const LoadOptions& options = {});

// Read and parse a file; load_rule_file picks the format by extension (.fis or .fll).
[[nodiscard]] bool load_fll(const std::string& path, Model& model, LoadError& error,
                            const LoadOptions& options = {});
[[nodiscard]] bool load_fis(const std::string& path, Model& model, LoadError& error,
                            const LoadOptions& options = {});
[[nodiscard]] bool load_rule_file(const std::string& path, Model& model, LoadError& error,
                                  const LoadOptions& options = {});

// Write a valid model as text, numbers at full precision (%.17g) so that reading it back gives
// the same model. Fails (with `error` set) when the format cannot express the model: .fis has a
// single defuzzifier and aggregation for all outputs and no lock-range or finite default, and
// neither format has singleton terms (shoulders are written as trapezoids with infinite feet).
// The load options (exact centroid, .fis resolution) are not stored in either format.
[[nodiscard]] bool to_fll(const Model& m, std::string& out, std::string& error);
[[nodiscard]] bool to_fis(const Model& m, std::string& out, std::string& error);

}  // namespace fuzzypid::io
