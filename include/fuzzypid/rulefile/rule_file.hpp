// Loading and saving rule bases as MATLAB Fuzzy Logic Toolbox `.fis`, fuzzylite `.fll` and
// IEC 61131-7 Fuzzy Control Language `.fcl` files (library fuzzypid::rulefile; see
// docs/rule_files.md for the supported constructs).
//
// Loading allocates and parses text; it happens once, outside the control loop. What the engine
// cannot represent exactly is refused with the file, line and the construct by its name in the
// file -- never approximated. The loaded fuzzy::EngineModel<double> then runs allocation-free
// through fuzzy::Engine or, for FuzzyPid, supervisor::EngineSupervisor.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "fuzzypid/fuzzy/engine.hpp"

namespace fuzzypid::rulefile {

using Model = fuzzy::EngineModel<double>;

struct LoadError {
  std::string file;     // the path or source name given to the loader
  int line = 0;         // 1-based; 0 when the problem concerns the whole file
  std::string message;  // what is wrong, naming the unsupported or malformed item
  // Set on success too: "file:line: ..." for what loads by a documented rule but may not mean
  // what the author meant (a term name repeated in a .fll or .fcl variable: rules naming it mean
  // the first such term, as fuzzylite's Variable::getTerm resolves it).
  std::vector<std::string> warnings;

  // "file:line: message" (or "file: message" when line is 0).
  std::string to_string() const;
};

struct LoadOptions {
  // Samples of the integral defuzzifiers for .fis and .fcl files, which do not state one
  // (fuzzylite's importers use 100; MATLAB samples 101 points including both ends -- see the docs).
  int fis_resolution = 100;
  // Compute Centroid in closed form instead of sampling (all output terms must be piecewise
  // linear, or loading fails). Not stored in the files.
  bool exact_centroid = false;
};

// Parse `text` as the named format; `source` names it in errors. On failure `model` is left in an
// unspecified state and `error` says why. The model is sized to the file: loading allocates its
// arrays with the file's exact counts (docs/rule_files.md), evaluation allocates nothing.
[[nodiscard]] bool parse_fll(std::string_view text, const std::string& source, Model& model,
                             LoadError& error, const LoadOptions& options = {});
[[nodiscard]] bool parse_fis(std::string_view text, const std::string& source, Model& model,
                             LoadError& error, const LoadOptions& options = {});
[[nodiscard]] bool parse_fcl(std::string_view text, const std::string& source, Model& model,
                             LoadError& error, const LoadOptions& options = {});

// Read and parse a file; load_rule_file picks the format by extension (.fis, .fll or .fcl, any
// case).
[[nodiscard]] bool load_fll(const std::string& path, Model& model, LoadError& error,
                            const LoadOptions& options = {});
[[nodiscard]] bool load_fis(const std::string& path, Model& model, LoadError& error,
                            const LoadOptions& options = {});
[[nodiscard]] bool load_fcl(const std::string& path, Model& model, LoadError& error,
                            const LoadOptions& options = {});
[[nodiscard]] bool load_rule_file(const std::string& path, Model& model, LoadError& error,
                                  const LoadOptions& options = {});

// Write a valid model as text, numbers at full precision (%.17g) so that reading it back gives
// the same model. Fails (with `error` set) when the format cannot express the model: .fis has one
// rule block, a single defuzzifier and aggregation for all outputs, no lock-range, lock-previous,
// finite default or term height, no output in an antecedent, and only rules whose connectives are
// all `and` or all `or` over distinct inputs; no format has singleton or shoulder terms other than
// as trapezoids with infinite feet. .fll and .fcl need names of letters, digits, '_' and '.': other
// names are written sanitised the way fuzzylite does (other characters dropped), with "_2", "_3",
// ... appended where two would then coincide. The load options (exact centroid, .fis resolution)
// are not stored.
[[nodiscard]] bool to_fll(const Model& m, std::string& out, std::string& error);
[[nodiscard]] bool to_fis(const Model& m, std::string& out, std::string& error);
[[nodiscard]] bool to_fcl(const Model& m, std::string& out, std::string& error);

}  // namespace fuzzypid::rulefile
