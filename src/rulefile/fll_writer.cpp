// fuzzylite .fll writer, as fuzzylite's FllExporter writes the format (fll_reader.cpp reads it
// and describes the grammar). A model the format cannot express is refused with the reason.
#include <string>

#include "check.hpp"
#include "formula.hpp"
#include "fuzzypid/rulefile/rule_file.hpp"
#include "rules.hpp"
#include "terms.hpp"
#include "text.hpp"

namespace fuzzypid::rulefile {

bool to_fll(const Model& m, std::string& out, std::string& error) {
  if (!check_export(m, error)) return false;
  if (error = beyond_fuzzylite_formats(m); !error.empty()) return false;
  const rules::ExportNames names = rules::export_names(m);
  using text::format_number;
  std::string s = "Engine: " + text::sanitized(text::name_of(m.name)) + "\n";
  for (std::size_t i = 0; i < m.num_inputs; ++i) {
    const auto& in = m.inputs[i];
    s += "InputVariable: " + names.inputs[i] + "\n  enabled: " + (in.enabled ? "true" : "false") +
         "\n";
    s += "  range: " + format_number(in.min) + " " + format_number(in.max) + "\n";
    s += std::string("  lock-range: ") + (in.lock_range ? "true" : "false") + "\n";
    for (std::size_t t = 0; t < in.num_terms; ++t) {
      const std::string w = terms::write_membership(terms::Format::Fll, in.terms[t], m);
      if (w.empty()) {
        error = "input term '" + std::string(text::name_of(in.term_names[t])) +
                "' has a shape .fll cannot express";
        return false;
      }
      s += "  term: " + names.input_terms[i][t] + " " + w + "\n";
    }
  }
  for (std::size_t o = 0; o < m.num_outputs; ++o) {
    const auto& v = m.outputs[o];
    const bool sugeno = fuzzy::is_sugeno(v.defuzzifier);
    s += "OutputVariable: " + names.outputs[o] + "\n  enabled: " + (v.enabled ? "true" : "false") +
         "\n";
    s += "  range: " + format_number(v.min) + " " + format_number(v.max) + "\n";
    s += std::string("  lock-range: ") + (v.lock_range ? "true" : "false") + "\n";
    s += std::string("  aggregation: ") +
         (!v.has_aggregation ? "none" : fuzzy::names(v.aggregation).fuzzylite) + "\n";
    s += std::string("  defuzzifier: ") + fuzzy::names(v.defuzzifier).fuzzylite +
         (!sugeno ? " " + std::to_string(v.resolution)
          : v.num_terms > 0 && v.terms[0].kind == fuzzy::OutputTermKind::Membership
              ? std::string(" Tsukamoto")
              : std::string(" TakagiSugeno")) +
         "\n";
    s += "  default: " + format_number(v.default_value) +
         "\n  lock-previous: " + (v.lock_previous ? "true" : "false") + "\n";
    for (std::size_t t = 0; t < v.num_terms; ++t) {
      const auto& term = v.terms[t];
      std::string w;
      if (term.kind == fuzzy::OutputTermKind::Constant) {
        w = "Constant " + format_number(term.coefficients[0]);
      } else if (term.kind == fuzzy::OutputTermKind::Linear) {
        w = "Linear";
        for (std::size_t c = 0; c <= m.num_inputs; ++c)
          w += " " + format_number(term.coefficients[c]);
      } else {
        w = terms::write_membership(terms::Format::Fll, term.membership, m);
      }
      if (w.empty()) {
        error = "output term '" + std::string(text::name_of(v.term_names[t])) +
                "' has a shape .fll cannot express";
        return false;
      }
      s += "  term: " + names.output_terms[o][t] + " " + w + "\n";
    }
  }
  for (std::size_t b = 0; b < m.num_blocks; ++b) {
    const auto& block = m.blocks[b];
    const std::string name(text::name_of(block.name));
    s += "RuleBlock: " + text::sanitized(name.empty() ? std::string("rules") : name) +
         "\n  enabled: true\n";
    s += std::string("  conjunction: ") +
         (block.has_conjunction ? fuzzy::names(block.conjunction).fuzzylite : "none") + "\n";
    s += std::string("  disjunction: ") +
         (block.has_disjunction ? fuzzy::names(block.disjunction).fuzzylite : "none") + "\n";
    s += std::string("  implication: ") +
         (block.has_implication ? fuzzy::names(block.implication).fuzzylite : "none") + "\n";
    std::string act = fuzzypid::name_of(fuzzy::kActivationNames, block.activation);
    switch (block.activation) {
      case fuzzy::ActivationMethod::Threshold:
        act += std::string(" ") + fuzzypid::name_of(fuzzy::kComparisonNames, block.comparison) +
               " " + format_number(block.threshold);
        break;
      case fuzzy::ActivationMethod::First:
      case fuzzy::ActivationMethod::Last:
        act += " " + std::to_string(block.count) + " " + format_number(block.threshold);
        break;
      case fuzzy::ActivationMethod::Highest:
      case fuzzy::ActivationMethod::Lowest:
        act += " " + std::to_string(block.count);
        break;
      default:
        break;
    }
    s += "  activation: " + act + "\n";
    for (std::size_t r = 0; r < m.num_rules; ++r)
      if (m.rules[r].block == b) s += "  rule: " + rules::write_rule(m, r, names) + "\n";
  }
  out = std::move(s);
  return true;
}

}  // namespace fuzzypid::rulefile
