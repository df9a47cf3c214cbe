// MATLAB Fuzzy Logic Toolbox .fis writer (fis_reader.cpp reads the format): the [System],
// [InputN], [OutputN] and [Rules] sections as MATLAB's writefis and Octave write them. A model
// that .fis cannot express (several rule blocks, an activation method, per-output defuzzifiers,
// locks and defaults, rules that are not one row of term codes, ...) is refused with the reason.
#include <cmath>
#include <string>
#include <vector>

#include "check.hpp"
#include "fuzzypid/rulefile/rule_file.hpp"
#include "rules.hpp"
#include "terms.hpp"
#include "text.hpp"

namespace fuzzypid::rulefile {

namespace {

using fuzzy::Hedge;
using fuzzy::SNorm;
using fuzzy::Token;

// A rule's antecedent as MATLAB's row: one code per input joined all by and or all by or; false
// when the rule does not have that form.
bool matlab_row(const Model& m, const fuzzy::Rule<double>& rule, std::vector<double>& codes,
                bool& disjunction, std::string& why) {
  codes.assign(m.num_inputs, 0.0);
  int connective = 0;  // 0 none yet, 1 and, 2 or
  for (std::size_t k = 0; k < rule.num_tokens; ++k) {
    const Token& t = m.tokens[rule.first_token + k];
    if (t.kind != Token::Kind::Proposition) {
      const int c = t.kind == Token::Kind::And ? 1 : 2;
      if (connective != 0 && connective != c) {
        why = "a rule mixes 'and' and 'or'";
        return false;
      }
      connective = c;
      // Postfix of a left fold: operators follow the second and later propositions.
      if (k < 2 || m.tokens[rule.first_token + k - 1].kind != Token::Kind::Proposition) {
        why = "a rule groups propositions with parentheses";
        return false;
      }
      continue;
    }
    if (codes[t.input] != 0.0) {
      why = "a rule names an input twice";
      return false;
    }
    double code = t.term == Token::kAnyTerm ? 0.0 : t.term + 1.0;
    bool negate = false;
    std::size_t h = 0;
    if (h < t.num_hedges && t.hedges[h] == Hedge::Not) {
      negate = true;
      ++h;
    }
    // The codes Octave reads as the same power (decode); seldom and extremely have none (.01 and
    // .3 are Octave's mu^0.1 and mu^3).
    if (t.power_tenths != 0 && h == t.num_hedges) {
      code += t.power_tenths / 100.0;
    } else if (h < t.num_hedges && t.power_tenths == 0) {
      const std::size_t rest = t.num_hedges - h;
      const Hedge first = t.hedges[h];
      if (rest == 2 && first == Hedge::Very && t.hedges[h + 1] == Hedge::Very) {
        code += 0.4;
      } else if (rest == 1 && first == Hedge::Somewhat) {
        code += 0.05;
      } else if (rest == 1 && first == Hedge::Very) {
        code += 0.2;
      } else if (rest == 1 && first == Hedge::Any) {
        code = 0.99;
      } else {
        why =
            "a rule has hedges .fis cannot encode (Octave reads .01 as mu^0.1 and .3 as mu^3, "
            "not seldom and extremely)";
        return false;
      }
    } else if (h < t.num_hedges) {
      why = "a rule has hedges .fis cannot encode";
      return false;
    }
    codes[t.input] = negate ? -code : code;
  }
  disjunction = connective == 2;
  return true;
}

// Every term of `v` is a constant and no two have the same value.
bool distinct_constants(const fuzzy::OutputSpec<double>& v) {
  for (std::size_t t = 0; t < v.num_terms; ++t) {
    if (v.terms[t].kind != fuzzy::OutputTermKind::Constant) return false;
    for (std::size_t u = 0; u < t; ++u)
      if (v.terms[u].coefficients[0] == v.terms[t].coefficients[0]) return false;
  }
  return true;
}

}  // namespace

bool to_fis(const Model& m, std::string& out, std::string& error) {
  if (!check_export(m, error)) return false;
  if (m.num_blocks != 1) {
    error = ".fis has one rule block, the model has " + std::to_string(m.num_blocks);
    return false;
  }
  const auto& block = m.blocks[0];
  if (block.activation != fuzzy::ActivationMethod::General) {
    error = std::string(".fis has no activation method (the model's block uses ") +
            fuzzypid::name_of(fuzzy::kActivationNames, block.activation) + ")";
    return false;
  }
  const auto& first = m.outputs[0];
  for (std::size_t o = 0; o < m.num_outputs; ++o) {
    const auto& v = m.outputs[o];
    if (v.defuzzifier != first.defuzzifier ||
        (!fuzzy::is_sugeno(v.defuzzifier) && v.aggregation != first.aggregation)) {
      error = ".fis cannot express per-output defuzzifiers or aggregations; output '" +
              std::string(text::name_of(v.name)) + "' differs from the first";
      return false;
    }
    if (v.lock_range || v.lock_previous || v.default_value == v.default_value) {
      error = "output '" + std::string(text::name_of(v.name)) +
              "' has lock-range, lock-previous or a default value, which .fis cannot express";
      return false;
    }
    if (!(std::isfinite(v.min) && std::isfinite(v.max))) {
      error = "output '" + std::string(text::name_of(v.name)) + "' has an infinite range";
      return false;
    }
    if (!fuzzy::is_sugeno(v.defuzzifier) && v.resolution != 100) {
      error = "output '" + std::string(text::name_of(v.name)) + "' has resolution " +
              std::to_string(v.resolution) + "; .fis has none (readers use 100)";
      return false;
    }
  }
  for (std::size_t i = 0; i < m.num_inputs; ++i) {
    if (m.inputs[i].lock_range || !std::isfinite(m.inputs[i].min) ||
        !std::isfinite(m.inputs[i].max)) {
      error = "input '" + std::string(text::name_of(m.inputs[i].name)) +
              "' has lock-range or an infinite range, which .fis cannot express";
      return false;
    }
  }
  // .fis quotes every name with ' and has no escape, so a name holding a quote cannot be written.
  const auto quotable = [&](const fuzzy::Name& name, const char* what) {
    if (text::name_of(name).find('\'') == std::string_view::npos) return true;
    error = std::string(what) + " name \"" + std::string(text::name_of(name)) +
            "\" holds a quote ('), which .fis cannot express";
    return false;
  };
  if (!quotable(m.name, "system")) return false;
  for (std::size_t i = 0; i < m.num_inputs; ++i) {
    if (!quotable(m.inputs[i].name, "input")) return false;
    for (std::size_t t = 0; t < m.inputs[i].num_terms; ++t)
      if (!quotable(m.inputs[i].term_names[t], "term")) return false;
  }
  for (std::size_t o = 0; o < m.num_outputs; ++o) {
    if (!quotable(m.outputs[o].name, "output")) return false;
    for (std::size_t t = 0; t < m.outputs[o].num_terms; ++t)
      if (!quotable(m.outputs[o].term_names[t], "term")) return false;
  }
  if (m.chained) {
    error = "a rule tests an output variable, which .fis cannot express";
    return false;
  }
  using text::format_number;
  const bool sugeno = fuzzy::is_sugeno(first.defuzzifier);
  bool tsukamoto = false;
  for (std::size_t o = 0; o < m.num_outputs; ++o)
    tsukamoto = tsukamoto || (sugeno && m.outputs[o].num_terms > 0 &&
                              m.outputs[o].terms[0].kind == fuzzy::OutputTermKind::Membership);
  std::string s = "[System]\n";
  s += "Name=" + text::quoted(text::name_of(m.name)) + "\n";
  s += std::string("Type='") +
       (tsukamoto ? "tsukamoto"
        : sugeno  ? "sugeno"
                  : "mamdani") +
       "'\nVersion=2.0\n";
  s += "NumInputs=" + std::to_string(m.num_inputs) + "\n";
  s += "NumOutputs=" + std::to_string(m.num_outputs) + "\n";
  s += "NumRules=" + std::to_string(m.num_rules) + "\n";
  s += std::string("AndMethod='") +
       (block.has_conjunction ? fuzzy::names(block.conjunction).fis : "") + "'\n";
  s += std::string("OrMethod='") +
       (block.has_disjunction ? fuzzy::names(block.disjunction).fis : "") + "'\n";
  s += std::string("ImpMethod='") +
       (block.has_implication ? fuzzy::names(block.implication).fis : "") + "'\n";
  std::string aggregation = first.has_aggregation ? fuzzy::names(first.aggregation).fis : "";
  if (sugeno) {
    // Under a weighted DefuzzMethod, AggMethod says whether equal singletons merge (Octave; our
    // reader sets merge_equal_singletons for any s-norm but sum): only 'sum' writes an output
    // that weighs every conclusion (fuzzylite's weighted average, whatever its aggregation).
    bool merging = false, plain = false, differ = false;
    SNorm merge_with = SNorm::Maximum;
    for (std::size_t o = 0; o < m.num_outputs; ++o) {
      const auto& v = m.outputs[o];
      // fuzzylite 8's grouping by term is Octave's merging of equal values when the terms are
      // constants of distinct values; it changes nothing when no term is concluded twice.
      const bool grouped =
          v.group_by_term && fuzzy::fuzzylite8_groups_by_term(v) && concludes_a_term_twice(m, o);
      if (grouped && !distinct_constants(v)) {
        error = "output '" + std::string(text::name_of(v.name)) +
                "' aggregates the activations of each term (fuzzylite 8's weighted "
                "defuzzification); .fis can only merge equal values (Octave), which is the same "
                "only for constant terms of distinct values";
        return false;
      }
      if (v.num_terms == 0 || v.terms[0].kind == fuzzy::OutputTermKind::Membership) continue;
      if (v.merge_equal_singletons || grouped) {
        differ = differ || (merging && v.aggregation != merge_with);
        merging = true;
        merge_with = v.aggregation;
      } else if (v.has_aggregation && v.aggregation != SNorm::UnboundedSum) {
        plain = true;
      }
    }
    if ((merging && plain) || differ) {
      error =
          ".fis has one AggMethod: some Sugeno outputs merge equal singletons with their "
          "aggregation (Octave's) and others weigh every conclusion, or they merge with "
          "different aggregations";
      return false;
    }
    if (merging) aggregation = fuzzy::names(merge_with).fis;
    if (plain) aggregation = "sum";
  }
  s += "AggMethod='" + aggregation + "'\n";
  s += std::string("DefuzzMethod='") + fuzzy::names(first.defuzzifier).fis + "'\n";
  // A disabled variable is written with fuzzylite's Enabled=0 (MATLAB has no such key).
  const auto variable = [&](const char* kind, std::size_t index, const fuzzy::Name& name, double lo,
                            double hi, std::size_t n, bool enabled) {
    s += "\n[" + std::string(kind) + std::to_string(index + 1) + "]\n";
    s += "Name=" + text::quoted(text::name_of(name)) + "\n";
    if (!enabled) s += "Enabled=0\n";
    s += "Range=[" + format_number(lo) + " " + format_number(hi) + "]\n";
    s += "NumMFs=" + std::to_string(n) + "\n";
  };
  for (std::size_t i = 0; i < m.num_inputs; ++i) {
    const auto& in = m.inputs[i];
    variable("Input", i, in.name, in.min, in.max, in.num_terms, in.enabled);
    for (std::size_t t = 0; t < in.num_terms; ++t) {
      const std::string w = terms::write_membership(terms::Format::Fis, in.terms[t], m);
      if (w.empty()) {
        error = "input term '" + std::string(text::name_of(in.term_names[t])) +
                (in.terms[t].shape == fuzzy::Shape::Function
                     ? "': " + std::string(terms::kFisFunction)
                     : "' has a shape or height .fis cannot express");
        return false;
      }
      s += "MF" + std::to_string(t + 1) + "=" + text::quoted(text::name_of(in.term_names[t])) +
           ":" + w + "\n";
    }
  }
  for (std::size_t o = 0; o < m.num_outputs; ++o) {
    const auto& v = m.outputs[o];
    variable("Output", o, v.name, v.min, v.max, v.num_terms, v.enabled);
    for (std::size_t t = 0; t < v.num_terms; ++t) {
      const auto& term = v.terms[t];
      std::string w;
      if (term.kind == fuzzy::OutputTermKind::Constant) {
        w = "'constant',[" + format_number(term.coefficients[0]) + "]";
      } else if (term.kind == fuzzy::OutputTermKind::Linear) {
        w = "'linear',[";
        for (std::size_t c = 0; c <= m.num_inputs; ++c)
          w += (c ? " " : "") + format_number(term.coefficients[c]);
        w += "]";
      } else {
        w = terms::write_membership(terms::Format::Fis, term.membership, m);
      }
      if (w.empty()) {
        error = "output term '" + std::string(text::name_of(v.term_names[t])) +
                (term.membership.shape == fuzzy::Shape::Function
                     ? "': " + std::string(terms::kFisFunction)
                     : "' has a shape or height .fis cannot express");
        return false;
      }
      s += "MF" + std::to_string(t + 1) + "=" + text::quoted(text::name_of(v.term_names[t])) + ":" +
           w + "\n";
    }
  }
  s += "\n[Rules]\n";
  for (std::size_t r = 0; r < m.num_rules; ++r) {
    const auto& rule = m.rules[r];
    std::vector<double> codes;
    bool disjunction = false;
    std::string why;
    if (!matlab_row(m, rule, codes, disjunction, why)) {
      error = "rule " + std::to_string(r + 1) + ": " + why + ", which .fis cannot express";
      return false;
    }
    std::vector<double> outs(m.num_outputs, 0.0);
    double degree_hedges = 0;
    for (std::size_t k = 0; k < rule.num_conclusions; ++k) {
      const auto& c = m.conclusions[rule.first_conclusion + k];
      degree_hedges += c.num_hedges;
      outs[c.output] = c.term + 1.0 + c.power_tenths / 100.0;  // Octave's hedge .dd
    }
    if (degree_hedges > 0) {
      error =
          "rule " + std::to_string(r + 1) + " has hedged conclusions, which .fis cannot express";
      return false;
    }
    std::string line;
    for (std::size_t i = 0; i < m.num_inputs; ++i)
      line += (i ? " " : "") + format_number(codes[i]);
    line += ",";
    for (std::size_t o = 0; o < m.num_outputs; ++o)
      line += " " + format_number(outs[o]);
    line += " (" + format_number(rule.weight) + ") : " + (disjunction ? "2" : "1");
    s += line + "\n";
  }
  out = std::move(s);
  return true;
}

}  // namespace fuzzypid::rulefile
