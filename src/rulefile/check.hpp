// The one semantic check of a model, shared by the three readers and the three writers:
// fuzzy::EngineModel's validate(), with a reader's finding placed on the line of the variable or
// rule concerned (private to fuzzypid::rulefile).
#pragma once

#include <string>
#include <vector>

#include "fuzzypid/rulefile/rule_file.hpp"

namespace fuzzypid::rulefile {

// Where each input, output and rule of the model was written.
// What the readers fill while parsing: a model of fixed capacity (FixedCapacity, on the heap),
// copied once parsed into a Model sized to the file (size_to_file).
using Builder = fuzzy::EngineModel<double, fuzzy::FixedCapacity>;

struct SourceLines {
  std::vector<int> inputs, outputs, rules;
};

// Validates `model`; on failure fills `error` (its file already set) and returns false.
bool check_model(const Builder& model, const SourceLines& lines, LoadError& error);

// Copies a checked `built` into `model`, allocating exactly the counts of the file.
bool size_to_file(const Builder& built, Model& model, LoadError& error);

// Validates a model about to be written; on failure sets `error` ("invalid model: ...") and
// returns false.
bool check_export(const Model& model, std::string& error);

// Whether some term of output `o` is concluded more than once by the rules: only then does
// grouping a weighted output's activations by term (OutputSpec::group_by_term) change its value.
bool concludes_a_term_twice(const Model& model, std::size_t o);

// What a model holds that fuzzylite's formats (.fll, .fcl, read as fuzzylite 8 computes them)
// cannot express: Octave's power hedges (.fis codes .dd other than .05, .2, .4), Sugeno outputs
// that merge equal singletons (both from a .fis as Octave computes it), and a weighted output
// that weighs every activation where fuzzylite 8 groups them by term and it makes a difference (a
// Tsukamoto .fis, read per activation as fuzzylite 6 reads it). Empty when there is none, else
// the first, named.
std::string beyond_fuzzylite_formats(const Model& model);

// Variable and rule limits of the capacity, as messages name them.
inline std::string capacity_text() {
  return std::to_string(Builder::Capacity::inputs) + " inputs, " +
         std::to_string(Builder::Capacity::outputs) + " outputs, " +
         std::to_string(Builder::Capacity::terms) + " terms per variable, " +
         std::to_string(Builder::Capacity::rules) + " rules";
}

}  // namespace fuzzypid::rulefile
