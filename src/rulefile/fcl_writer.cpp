// IEC 61131-7 Fuzzy Control Language (.fcl) writer, the subset fuzzylite 6's FclExporter writes
// (fcl_reader.cpp reads it and describes the grammar). A model the format cannot express is
// refused with the reason.
#include <string>

#include "check.hpp"
#include "formula.hpp"
#include "fuzzypid/rulefile/rule_file.hpp"
#include "rules.hpp"
#include "terms.hpp"
#include "text.hpp"

namespace fuzzypid::rulefile {

bool to_fcl(const Model& m, std::string& out, std::string& error) {
  if (!check_export(m, error)) return false;
  if (error = beyond_fuzzylite_formats(m); !error.empty()) return false;
  for (std::size_t i = 0; i < m.num_inputs + m.num_outputs; ++i) {
    const bool input = i < m.num_inputs;
    if (input ? m.inputs[i].enabled : m.outputs[i - m.num_inputs].enabled) continue;
    error =
        std::string(input ? "input '" : "output '") +
        std::string(text::name_of(input ? m.inputs[i].name : m.outputs[i - m.num_inputs].name)) +
        "' is disabled, which .fcl cannot express";
    return false;
  }
  const rules::ExportNames names = rules::export_names(m);
  using text::format_number;
  const auto range = [](double lo, double hi) {
    return "  RANGE := (" + format_number(lo) + " .. " + format_number(hi) + ");\n";
  };
  std::string s = "FUNCTION_BLOCK " + text::sanitized(text::name_of(m.name)) + "\n\nVAR_INPUT\n";
  for (std::size_t i = 0; i < m.num_inputs; ++i)
    s += "  " + names.inputs[i] + ": REAL;\n";
  s += "END_VAR\n\nVAR_OUTPUT\n";
  for (std::size_t o = 0; o < m.num_outputs; ++o)
    s += "  " + names.outputs[o] + ": REAL;\n";
  s += "END_VAR\n";
  for (std::size_t i = 0; i < m.num_inputs; ++i) {
    const auto& in = m.inputs[i];
    s += "\nFUZZIFY " + names.inputs[i] + "\n" + range(in.min, in.max);
    for (std::size_t t = 0; t < in.num_terms; ++t) {
      const std::string w = terms::write_membership(terms::Format::Fcl, in.terms[t], m);
      if (w.empty()) {
        error = "input term '" + std::string(text::name_of(in.term_names[t])) +
                "' has a shape .fcl cannot express";
        return false;
      }
      s += "  TERM " + names.input_terms[i][t] + " := " + w + ";\n";
    }
    if (in.lock_range) s += "  LOCK : RANGE;\n";
    s += "END_FUZZIFY\n";
  }
  for (std::size_t o = 0; o < m.num_outputs; ++o) {
    const auto& v = m.outputs[o];
    const bool sugeno = fuzzy::is_sugeno(v.defuzzifier);
    if (!sugeno && v.resolution != 100) {
      error = "output '" + std::string(text::name_of(v.name)) + "' has resolution " +
              std::to_string(v.resolution) + "; .fcl has none (readers use 100)";
      return false;
    }
    s += "\nDEFUZZIFY " + names.outputs[o] + "\n" + range(v.min, v.max);
    for (std::size_t t = 0; t < v.num_terms; ++t) {
      const auto& term = v.terms[t];
      std::string w;
      if (term.kind == fuzzy::OutputTermKind::Constant) {
        w = format_number(term.coefficients[0]);
      } else if (term.kind == fuzzy::OutputTermKind::Linear) {
        w = "Linear";
        for (std::size_t c = 0; c <= m.num_inputs; ++c)
          w += " " + format_number(term.coefficients[c]);
      } else {
        w = terms::write_membership(terms::Format::Fcl, term.membership, m);
      }
      if (w.empty()) {
        error = "output term '" + std::string(text::name_of(v.term_names[t])) +
                "' has a shape .fcl cannot express";
        return false;
      }
      s += "  TERM " + names.output_terms[o][t] + " := " + w + ";\n";
    }
    s += std::string("  METHOD : ") + fuzzy::names(v.defuzzifier).fcl + ";\n";
    if (v.has_aggregation) s += std::string("  ACCU : ") + fuzzy::names(v.aggregation).fcl + ";\n";
    s +=
        "  DEFAULT := " + format_number(v.default_value) + (v.lock_previous ? " | NC" : "") + ";\n";
    if (v.lock_range) s += "  LOCK : RANGE;\n";
    s += "END_DEFUZZIFY\n";
  }
  for (std::size_t b = 0; b < m.num_blocks; ++b) {
    const auto& block = m.blocks[b];
    if (block.activation != fuzzy::ActivationMethod::General) {
      error = std::string(".fcl has no activation method (a block uses ") +
              fuzzypid::name_of(fuzzy::kActivationNames, block.activation) + ")";
      return false;
    }
    const std::string name(text::name_of(block.name));
    s += "\nRULEBLOCK " + text::sanitized(name.empty() ? std::string("rules") : name) + "\n";
    if (block.has_conjunction)
      s += std::string("  AND : ") + fuzzy::names(block.conjunction).fcl + ";\n";
    if (block.has_disjunction)
      s += std::string("  OR : ") + fuzzy::names(block.disjunction).fcl + ";\n";
    if (block.has_implication)
      s += std::string("  ACT : ") + fuzzy::names(block.implication).fcl + ";\n";
    std::size_t n = 0;
    for (std::size_t r = 0; r < m.num_rules; ++r)
      if (m.rules[r].block == b)
        s += "  RULE " + std::to_string(++n) + " : " + rules::write_rule(m, r, names) + ";\n";
    s += "END_RULEBLOCK\n";
  }
  s += "\nEND_FUNCTION_BLOCK\n";
  out = std::move(s);
  return true;
}

}  // namespace fuzzypid::rulefile
