// The one semantic check of a loaded model, shared by the three readers: fuzzy::EngineModel's
// validate(), with its finding placed on the line of the variable or rule concerned (private to
// fuzzypid::rulefile).
#pragma once

#include <string>
#include <vector>

#include "fuzzypid/rulefile/rule_file.hpp"

namespace fuzzypid::rulefile {

// Where each input, output and rule of the model was written.
struct SourceLines {
  std::vector<int> inputs, outputs, rules;
};

// Validates `model`; on failure fills `error` (its file already set) and returns false.
bool check_model(const Model& model, const SourceLines& lines, LoadError& error);

// True when the names sanitised for .fll/.fcl stay distinct (variables; terms of a variable).
bool check_sanitized_names(const Model& m, std::string& error);

// Variable and rule limits of the capacity, as messages name them.
inline std::string capacity_text() {
  return std::to_string(Model::Capacity::inputs) + " inputs, " +
         std::to_string(Model::Capacity::outputs) + " outputs, " +
         std::to_string(Model::Capacity::terms) + " terms per variable, " +
         std::to_string(Model::Capacity::rules) + " rules";
}

}  // namespace fuzzypid::rulefile
