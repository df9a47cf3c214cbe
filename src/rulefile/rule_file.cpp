// File access, format dispatch and the shared model check of the rule-file readers.
#include "fuzzypid/rulefile/rule_file.hpp"
#include "fuzzypid/fuzzy/engine_model_copy.hpp"
#include "fuzzypid/fuzzy/engine_model_validation.hpp"
#include "fuzzypid_support/bounded_read.hpp"
#include "fuzzypid_support/printable.hpp"

#include <string>
#include <vector>

#include "check.hpp"
#include "text.hpp"

namespace fuzzypid::rulefile {

std::string LoadError::to_string() const {
  // The message quotes the file's text, which may be any bytes (a binary file): never raw.
  const std::string text = support::printable(message);
  return line > 0 ? file + ":" + std::to_string(line) + ": " + text : file + ": " + text;
}

bool check_model(const Builder& model, const SourceLines& lines, LoadError& error) {
  if (model.num_rules == 0) {
    error.line = 0;
    error.message = "no rules";
    return false;
  }
  const fuzzy::ModelError e = fuzzy::validate(model);
  if (!e) return true;
  using Where = fuzzy::ModelError::Where;
  const auto at = [&](const std::vector<int>& v) { return e.index < v.size() ? v[e.index] : 0; };
  std::string what;
  switch (e.where) {
    case Where::Input:
      error.line = at(lines.inputs);
      what = "input '" + std::string(text::name_of(model.inputs[e.index].name)) + "': ";
      break;
    case Where::Output:
      error.line = at(lines.outputs);
      what = "output '" + std::string(text::name_of(model.outputs[e.index].name)) + "': ";
      break;
    case Where::Rule:
      error.line = at(lines.rules);
      what = "rule " + std::to_string(e.index + 1) + ": ";
      break;
    case Where::Model:
      error.line = 0;
      break;
  }
  error.message = what + e.message;
  return false;
}

bool size_to_file(const Builder& built, Model& model, LoadError& error) {
  if (fuzzy::copy_model(built, model)) return true;
  error.line = 0;
  error.message = "the model does not fit its storage";
  return false;
}

bool check_export(const Model& model, std::string& error) {
  const fuzzy::ModelError e = fuzzy::validate(model);
  if (e) error = std::string("invalid model: ") + e.message;
  return !e;
}

bool concludes_a_term_twice(const Model& m, std::size_t o) {
  std::vector<unsigned> count(m.outputs[o].num_terms, 0);
  for (std::size_t k = 0; k < m.num_conclusions; ++k)
    if (m.conclusions[k].output == o && ++count[m.conclusions[k].term] > 1) return true;
  return false;
}

std::string beyond_fuzzylite_formats(const Model& m) {
  for (std::size_t o = 0; o < m.num_outputs; ++o) {
    const auto& out = m.outputs[o];
    const std::string name = "output '" + std::string(text::name_of(out.name)) + "'";
    if (out.merge_equal_singletons)
      return name +
             " merges equal singletons with its aggregation (Octave's Sugeno aggregation of a "
             ".fis), which fuzzylite's formats cannot express";
    // The other way round (grouped where fuzzylite 8 would not) gives the same value.
    if (!out.group_by_term && fuzzy::fuzzylite8_groups_by_term(out) && concludes_a_term_twice(m, o))
      return name +
             " weighs every activation of a term concluded more than once (a .fis read as "
             "fuzzylite 6 reads it), where fuzzylite 8 aggregates them per term under this "
             "defuzzifier and aggregation; fuzzylite's formats cannot express it";
  }
  for (std::size_t r = 0; r < m.num_rules; ++r) {
    const auto& rule = m.rules[r];
    bool power = false;
    for (std::size_t k = 0; k < rule.num_tokens; ++k)
      power = power || m.tokens[rule.first_token + k].power_tenths != 0;
    for (std::size_t k = 0; k < rule.num_conclusions; ++k)
      power = power || m.conclusions[rule.first_conclusion + k].power_tenths != 0;
    if (power)
      return "rule " + std::to_string(r + 1) +
             " has Octave's power hedge (a .fis code .dd other than .05, .2, .4), which "
             "fuzzylite's formats cannot express";
  }
  return {};
}

namespace {

// A rule base with the default capacity's 2,048 rules is well under 1 MiB; anything larger is
// refused before it can exhaust memory (a device or a FIFO is refused by its kind, unread).
constexpr std::size_t kMaxRuleFileBytes = std::size_t{16} << 20;

bool read_file(const std::string& path, std::string& text, LoadError& error) {
  std::string reason;
  if (!support::read_file_bounded(path, kMaxRuleFileBytes, text, reason)) {
    error = LoadError{path, 0, reason, {}};
    return false;
  }
  return true;
}

bool has_extension(const std::string& path, const char* ext) {
  const std::string e(ext);
  return path.size() >= e.size() && text::iequals(path.substr(path.size() - e.size()), e);
}

}  // namespace

bool load_fll(const std::string& path, Model& model, LoadError& error, const LoadOptions& options) {
  std::string text;
  return read_file(path, text, error) && parse_fll(text, path, model, error, options);
}

bool load_fis(const std::string& path, Model& model, LoadError& error, const LoadOptions& options) {
  std::string text;
  return read_file(path, text, error) && parse_fis(text, path, model, error, options);
}

bool load_fcl(const std::string& path, Model& model, LoadError& error, const LoadOptions& options) {
  std::string text;
  return read_file(path, text, error) && parse_fcl(text, path, model, error, options);
}

bool load_rule_file(const std::string& path, Model& model, LoadError& error,
                    const LoadOptions& options) {
  if (has_extension(path, ".fis")) return load_fis(path, model, error, options);
  if (has_extension(path, ".fll")) return load_fll(path, model, error, options);
  if (has_extension(path, ".fcl")) return load_fcl(path, model, error, options);
  error = LoadError{path, 0, "unknown rule file extension (expected .fis, .fll or .fcl)", {}};
  return false;
}

}  // namespace fuzzypid::rulefile
