// fuzzylite .fll reader and writer. The grammar is fuzzylite 6's FllImporter: one `key: value`
// per line, `#` starts a comment, sections Engine / InputVariable / OutputVariable / RuleBlock.
#include <cmath>
#include <string>
#include <vector>

#include "fuzzypid/io/rule_file.hpp"
#include "terms.hpp"
#include "text.hpp"

namespace fuzzypid::io {

namespace {

using fuzzy::Defuzzifier;
using fuzzy::kMaxInputs;
using fuzzy::kMaxOutputs;
using fuzzy::kMaxRules;
using fuzzy::kMaxTerms;
using fuzzy::SNorm;
using fuzzy::TNorm;

enum class Section { None, Engine, Input, Output, RuleBlock };

class FllParser {
 public:
  FllParser(const std::string& source, Model& model, LoadError& error, const LoadOptions& options)
      : model_(model), error_(error), options_(options) {
    error_ = LoadError{source, 0, {}};
  }

  bool parse(std::string_view text) {
    model_ = Model{};
    // Until a RuleBlock states them, the operators are unset.
    model_.conjunction = TNorm::None;
    model_.disjunction = SNorm::None;
    model_.implication = TNorm::None;
    for (const text::Line& line : text::split_lines(text)) {
      line_ = line.number;
      std::string_view s = line.text;
      const std::size_t hash = s.find('#');
      if (hash != std::string_view::npos) s = s.substr(0, hash);
      s = text::trim(s);
      if (s.empty()) continue;
      const std::size_t colon = s.find(':');
      if (colon == std::string_view::npos)
        return fail("expected 'key: value', got '" + std::string(s) + "'");
      if (!property(text::trim(s.substr(0, colon)), text::trim(s.substr(colon + 1)))) return false;
    }
    return finish();
  }

 private:
  bool fail(const std::string& message) {
    error_.line = line_;
    error_.message = message;
    return false;
  }

  bool property(std::string_view key, std::string_view value) {
    if (key == "Engine") {
      if (seen_engine_ || section_ != Section::None) return fail("'Engine:' must come first, once");
      seen_engine_ = true;
      section_ = Section::Engine;
      if (!fuzzy::set_name(model_.name, value.data(), value.size()))
        return fail("engine name longer than 31 bytes");
      return true;
    }
    if (!seen_engine_ && (key == "InputVariable" || key == "OutputVariable" || key == "RuleBlock"))
      return fail("'Engine:' must come first");
    if (key == "InputVariable" || key == "OutputVariable") {
      const bool input = key == "InputVariable";
      if (seen_rule_block_) return fail("variables must come before the RuleBlock");
      if (!check_new_variable_name(value)) return false;
      if (input) {
        if (model_.num_inputs == kMaxInputs) return fail("more than 8 input variables");
        auto& in = model_.inputs[model_.num_inputs++];
        (void)fuzzy::set_name(in.name, value.data(), value.size());
        input_lines_.push_back(line_);
        section_ = Section::Input;
      } else {
        if (model_.num_outputs == kMaxOutputs) return fail("more than 8 output variables");
        auto& out = model_.outputs[model_.num_outputs++];
        out = fuzzy::OutputSpec<double>{};
        (void)fuzzy::set_name(out.name, value.data(), value.size());
        out.exact_centroid = options_.exact_centroid;
        output_lines_.push_back(line_);
        defuzzifier_seen_.push_back(false);
        aggregation_seen_.push_back(false);
        section_ = Section::Output;
      }
      return true;
    }
    if (key == "RuleBlock") {
      if (seen_rule_block_) return fail("more than one RuleBlock is not supported");
      seen_rule_block_ = true;
      rule_block_line_ = line_;
      section_ = Section::RuleBlock;
      return true;
    }
    if (key == "description") return true;
    switch (section_) {
      case Section::None:
        return fail("'" + std::string(key) + ":' before any section");
      case Section::Engine:
        return fail("unknown Engine property '" + std::string(key) + "'");
      case Section::Input:
      case Section::Output:
        return variable_property(key, value);
      case Section::RuleBlock:
        return rule_block_property(key, value);
    }
    return fail("unreachable");
  }

  bool check_new_variable_name(std::string_view name) {
    if (!text::valid_identifier(name))
      return fail("variable name '" + std::string(name) +
                  "' must be letters, digits, '_' or '.' and not a rule keyword");
    if (name.size() > fuzzy::kMaxNameLength) return fail("variable name longer than 31 bytes");
    for (std::size_t i = 0; i < model_.num_inputs; ++i)
      if (text::name_of(model_.inputs[i].name) == name)
        return fail("duplicate variable name '" + std::string(name) + "'");
    for (std::size_t o = 0; o < model_.num_outputs; ++o)
      if (text::name_of(model_.outputs[o].name) == name)
        return fail("duplicate variable name '" + std::string(name) + "'");
    return true;
  }

  bool boolean(std::string_view value, bool& out) {
    if (value == "true") {
      out = true;
    } else if (value == "false") {
      out = false;
    } else {
      return fail("expected true or false, got '" + std::string(value) + "'");
    }
    return true;
  }

  bool variable_property(std::string_view key, std::string_view value) {
    const bool input = section_ == Section::Input;
    // The current variable is the last one declared of its kind (the other kind may have none).
    auto& in = model_.inputs[input ? model_.num_inputs - 1 : 0];
    auto& out = model_.outputs[input ? 0 : model_.num_outputs - 1];
    if (key == "enabled") {
      bool enabled = true;
      if (!boolean(value, enabled)) return false;
      return enabled ? true : fail("disabled variables are not supported");
    }
    if (key == "range") {
      const auto words = text::split_words(value);
      double lo = 0, hi = 0;
      if (words.size() != 2 || !text::parse_number(words[0], lo) ||
          !text::parse_number(words[1], hi))
        return fail("range takes two numbers, got '" + std::string(value) + "'");
      if (!(std::isfinite(lo) && std::isfinite(hi) && lo < hi))
        return fail("range must be finite with min < max, got '" + std::string(value) + "'");
      (input ? in.min : out.min) = lo;
      (input ? in.max : out.max) = hi;
      return true;
    }
    if (key == "lock-range") return boolean(value, input ? in.lock_range : out.lock_range);
    if (key == "term") return term(value);
    if (input) return fail("unknown InputVariable property '" + std::string(key) + "'");
    if (key == "aggregation") {
      aggregation_seen_.back() = true;
      if (value == "Maximum") {
        out.aggregation = fuzzy::Aggregation::Maximum;
      } else if (value == "UnboundedSum") {
        out.aggregation = fuzzy::Aggregation::Sum;
      } else if (value == "none") {
        aggregation_seen_.back() = false;
      } else {
        return fail("unsupported aggregation '" + std::string(value) +
                    "' (Maximum, UnboundedSum or none)");
      }
      return true;
    }
    if (key == "defuzzifier") return defuzzifier(value, out);
    if (key == "default") {
      double d = 0;
      if (!text::parse_number(value, d, true) || std::isinf(d))
        return fail("default must be a finite number or nan, got '" + std::string(value) + "'");
      out.default_value = d;
      return true;
    }
    if (key == "lock-previous") {
      bool lock = false;
      if (!boolean(value, lock)) return false;
      return lock ? fail("lock-previous: true is not supported (the engine is stateless)") : true;
    }
    return fail("unknown OutputVariable property '" + std::string(key) + "'");
  }

  bool defuzzifier(std::string_view value, fuzzy::OutputSpec<double>& out) {
    const auto words = text::split_words(value);
    if (words.empty()) return fail("defuzzifier needs a name");
    const std::string_view name = words[0];
    struct Named {
      const char* name;
      Defuzzifier d;
    };
    static const Named integral[] = {{"Centroid", Defuzzifier::Centroid},
                                     {"Bisector", Defuzzifier::Bisector},
                                     {"MeanOfMaximum", Defuzzifier::MeanOfMaximum},
                                     {"SmallestOfMaximum", Defuzzifier::SmallestOfMaximum},
                                     {"LargestOfMaximum", Defuzzifier::LargestOfMaximum}};
    for (const auto& n : integral) {
      if (name != n.name) continue;
      out.defuzzifier = n.d;
      out.resolution = 100;
      if (words.size() > 2) return fail("defuzzifier takes at most a resolution");
      if (words.size() == 2) {
        std::size_t r = 0;
        if (!text::parse_count(words[1], r) || r < 1 || r > 100000000)
          return fail("resolution must be an integer in 1..1e8, got '" + std::string(words[1]) +
                      "'");
        out.resolution = static_cast<int>(r);
      }
      defuzzifier_seen_.back() = true;
      return true;
    }
    if (name == "WeightedAverage" || name == "WeightedSum") {
      out.defuzzifier =
          name == "WeightedAverage" ? Defuzzifier::WeightedAverage : Defuzzifier::WeightedSum;
      if (words.size() > 2) return fail("defuzzifier takes at most a type");
      if (words.size() == 2 && words[1] != "Automatic" && words[1] != "TakagiSugeno")
        return fail("unsupported weighted defuzzifier type '" + std::string(words[1]) +
                    "' (Automatic or TakagiSugeno)");
      defuzzifier_seen_.back() = true;
      return true;
    }
    return fail("unsupported defuzzifier '" + std::string(name) + "'");
  }

  bool term(std::string_view value) {
    const bool input = section_ == Section::Input;
    const auto words = text::split_words(value);
    if (words.size() < 2) return fail("term needs a name, a type and parameters");
    const std::string_view name = words[0];
    const std::string_view type = words[1];
    if (!text::valid_identifier(name))
      return fail("term name '" + std::string(name) +
                  "' must be letters, digits, '_' or '.' and not a rule keyword");
    if (name.size() > fuzzy::kMaxNameLength) return fail("term name longer than 31 bytes");
    std::vector<double> p;
    for (std::size_t k = 2; k < words.size(); ++k) {
      double x = 0;
      if (!text::parse_number(words[k], x, true))
        return fail("term '" + std::string(name) + "': '" + std::string(words[k]) +
                    "' is not a number");
      p.push_back(x);
    }
    std::size_t& count = input ? model_.inputs[model_.num_inputs - 1].num_terms
                               : model_.outputs[model_.num_outputs - 1].num_terms;
    auto& names = input ? model_.inputs[model_.num_inputs - 1].term_names
                        : model_.outputs[model_.num_outputs - 1].term_names;
    for (std::size_t t = 0; t < count; ++t)
      if (text::name_of(names[t]) == name)
        return fail("duplicate term name '" + std::string(name) + "'");
    if (count == kMaxTerms) return fail("more than 16 terms in a variable");
    if (input) {
      auto& t = model_.inputs[model_.num_inputs - 1].terms[count];
      const std::string why = terms::make_membership(terms::Format::Fll, type, p, t);
      if (!why.empty()) return fail("term '" + std::string(name) + "': " + why);
    } else {
      auto& t = model_.outputs[model_.num_outputs - 1].terms[count];
      if (type == "Constant" || type == "Linear") {
        for (double x : p)
          if (!std::isfinite(x))
            return fail("term '" + std::string(name) + "': coefficients must be finite");
        if (type == "Constant") {
          if (p.size() != 1)
            return fail("term '" + std::string(name) + "': Constant takes 1 value");
          t.kind = fuzzy::OutputTermKind::Constant;
          t.coefficients[0] = p[0];
        } else {
          const std::size_t n = model_.num_inputs;
          if (p.size() != n && p.size() != n + 1)
            return fail("term '" + std::string(name) + "': Linear takes " + std::to_string(n) +
                        " or " + std::to_string(n + 1) + " coefficients, got " +
                        std::to_string(p.size()));
          t.kind = fuzzy::OutputTermKind::Linear;
          for (std::size_t k = 0; k < p.size(); ++k)
            t.coefficients[k] = p[k];
        }
      } else {
        t.kind = fuzzy::OutputTermKind::Membership;
        const std::string why = terms::make_membership(terms::Format::Fll, type, p, t.membership);
        if (!why.empty()) return fail("term '" + std::string(name) + "': " + why);
      }
    }
    (void)fuzzy::set_name(names[count], name.data(), name.size());
    ++count;
    return true;
  }

  bool rule_block_property(std::string_view key, std::string_view value) {
    if (key == "enabled") {
      bool enabled = true;
      if (!boolean(value, enabled)) return false;
      return enabled ? true : fail("a disabled RuleBlock is not supported");
    }
    if (key == "conjunction" || key == "implication") {
      TNorm& op = key == "conjunction" ? model_.conjunction : model_.implication;
      if (value == "Minimum") {
        op = TNorm::Minimum;
      } else if (value == "AlgebraicProduct") {
        op = TNorm::Product;
      } else if (value == "none") {
        op = TNorm::None;
      } else {
        return fail("unsupported " + std::string(key) + " '" + std::string(value) +
                    "' (Minimum, AlgebraicProduct or none)");
      }
      return true;
    }
    if (key == "disjunction") {
      if (value == "Maximum") {
        model_.disjunction = SNorm::Maximum;
      } else if (value == "AlgebraicSum") {
        model_.disjunction = SNorm::ProbabilisticSum;
      } else if (value == "none") {
        model_.disjunction = SNorm::None;
      } else {
        return fail("unsupported disjunction '" + std::string(value) +
                    "' (Maximum, AlgebraicSum or none)");
      }
      return true;
    }
    if (key == "activation") {
      if (value == "General" || value == "none") return true;
      return fail("unsupported activation '" + std::string(value) + "' (General)");
    }
    if (key == "rule") return rule(value);
    return fail("unknown RuleBlock property '" + std::string(key) + "'");
  }

  int find_input(std::string_view name) const {
    for (std::size_t i = 0; i < model_.num_inputs; ++i)
      if (text::name_of(model_.inputs[i].name) == name) return static_cast<int>(i);
    return -1;
  }
  int find_output(std::string_view name) const {
    for (std::size_t o = 0; o < model_.num_outputs; ++o)
      if (text::name_of(model_.outputs[o].name) == name) return static_cast<int>(o);
    return -1;
  }
  static int find_term(const std::array<fuzzy::Name, kMaxTerms>& names, std::size_t n,
                       std::string_view name) {
    for (std::size_t t = 0; t < n; ++t)
      if (text::name_of(names[t]) == name) return static_cast<int>(t);
    return -1;
  }

  // if A is [not] T {and|or B is [not] T} then O is T {and P is T} [with w]
  bool rule(std::string_view value) {
    if (model_.num_rules == kMaxRules) return fail("more than 512 rules");
    fuzzy::Rule<double> r;
    const auto w = text::split_words(value);
    std::size_t k = 0;
    const auto word = [&](std::size_t i) { return i < w.size() ? w[i] : std::string_view{}; };
    for (const auto& token : w)
      if (token.find('(') != std::string_view::npos || token.find(')') != std::string_view::npos)
        return fail("parentheses in rules are not supported: '" + std::string(value) + "'");
    if (word(k++) != "if") return fail("rule must start with 'if'");
    int joiner = 0;  // 0 unknown, 1 and, 2 or
    for (;;) {
      const std::string_view var = word(k++);
      const int i = find_input(var);
      if (i < 0) return fail("rule names unknown input variable '" + std::string(var) + "'");
      if (word(k++) != "is") return fail("expected 'is' after '" + std::string(var) + "'");
      bool negate = false;
      if (word(k) == "not") {
        negate = true;
        ++k;
      }
      const std::string_view tname = word(k++);
      static const char* const hedges[] = {"any", "extremely", "seldom", "somewhat", "very"};
      for (const char* h : hedges)
        if (tname == h) return fail("unsupported hedge '" + std::string(tname) + "'");
      const auto& in = model_.inputs[static_cast<std::size_t>(i)];
      const int t = find_term(in.term_names, in.num_terms, tname);
      if (t < 0)
        return fail("rule names unknown term '" + std::string(tname) + "' of input '" +
                    std::string(var) + "'");
      if (r.antecedent[static_cast<std::size_t>(i)] != 0)
        return fail("input '" + std::string(var) + "' appears twice in one rule (not supported)");
      r.antecedent[static_cast<std::size_t>(i)] =
          static_cast<std::int8_t>(negate ? -(t + 1) : t + 1);
      const std::string_view next = word(k++);
      if (next == "then") break;
      const int j = next == "and" ? 1 : next == "or" ? 2 : 0;
      if (j == 0) return fail("expected 'and', 'or' or 'then', got '" + std::string(next) + "'");
      if (joiner != 0 && joiner != j) return fail("rules mixing 'and' and 'or' are not supported");
      joiner = j;
    }
    r.disjunction = joiner == 2;
    for (;;) {
      const std::string_view var = word(k++);
      const int o = find_output(var);
      if (o < 0) return fail("rule names unknown output variable '" + std::string(var) + "'");
      if (word(k++) != "is") return fail("expected 'is' after '" + std::string(var) + "'");
      const std::string_view tname = word(k++);
      if (tname == "not") return fail("negated consequents are not supported");
      const auto& out = model_.outputs[static_cast<std::size_t>(o)];
      const int t = find_term(out.term_names, out.num_terms, tname);
      if (t < 0)
        return fail("rule names unknown term '" + std::string(tname) + "' of output '" +
                    std::string(var) + "'");
      if (r.consequent[static_cast<std::size_t>(o)] != 0)
        return fail("output '" + std::string(var) + "' appears twice in one rule");
      r.consequent[static_cast<std::size_t>(o)] = static_cast<std::int8_t>(t + 1);
      const std::string_view next = word(k++);
      if (next.empty()) break;
      if (next == "with") {
        double weight = 0;
        if (!text::parse_number(word(k++), weight) || !(weight >= 0 && weight <= 1))
          return fail("rule weight must be a number in [0, 1]");
        r.weight = weight;
        if (!word(k).empty()) return fail("unexpected '" + std::string(word(k)) + "' after weight");
        break;
      }
      if (next != "and") return fail("expected 'and' or 'with', got '" + std::string(next) + "'");
    }
    const std::size_t antecedents = [&] {
      std::size_t n = 0;
      for (auto a : r.antecedent)
        n += a != 0;
      return n;
    }();
    if (antecedents > 1 &&
        (r.disjunction ? model_.disjunction == SNorm::None : model_.conjunction == TNorm::None))
      return fail(std::string("rule uses '") + (r.disjunction ? "or" : "and") +
                  "' but the RuleBlock's " + (r.disjunction ? "disjunction" : "conjunction") +
                  " is none (state it before the rules)");
    model_.rules[model_.num_rules++] = r;
    return true;
  }

  bool finish() {
    if (!seen_engine_) {
      line_ = 0;
      return fail("missing 'Engine:' line");
    }
    if (model_.num_inputs == 0) return fail_at(0, "no InputVariable");
    if (model_.num_outputs == 0) return fail_at(0, "no OutputVariable");
    for (std::size_t i = 0; i < model_.num_inputs; ++i)
      if (model_.inputs[i].num_terms == 0) return fail_at(input_lines_[i], "input has no terms");
    bool mamdani = false;
    for (std::size_t o = 0; o < model_.num_outputs; ++o) {
      const auto& out = model_.outputs[o];
      const int at = output_lines_[o];
      if (out.num_terms == 0) return fail_at(at, "output has no terms");
      if (!defuzzifier_seen_[o]) return fail_at(at, "output has no defuzzifier");
      const bool sugeno = fuzzy::is_sugeno(out.defuzzifier);
      for (std::size_t t = 0; t < out.num_terms; ++t) {
        const bool membership = out.terms[t].kind == fuzzy::OutputTermKind::Membership;
        if (membership == sugeno)
          return fail_at(at, std::string("term '") + out.term_names[t].data() + "' " +
                                 (sugeno ? "must be Constant or Linear for a weighted defuzzifier"
                                         : "must be a membership function for an integral "
                                           "defuzzifier"));
        if (membership && out.exact_centroid && out.defuzzifier == Defuzzifier::Centroid &&
            !fuzzy::is_piecewise_linear(out.terms[t].membership))
          return fail_at(at, std::string("term '") + out.term_names[t].data() +
                                 "' is not piecewise linear (exact centroid requested)");
      }
      if (!sugeno && !aggregation_seen_[o])
        return fail_at(at, "output needs an aggregation (Maximum or UnboundedSum)");
      mamdani = mamdani || !sugeno;
    }
    if (model_.num_rules == 0) return fail_at(rule_block_line_, "no rules");
    if (mamdani && model_.implication == TNorm::None)
      return fail_at(rule_block_line_, "the RuleBlock needs an implication for Mamdani outputs");
    if (model_.conjunction == TNorm::None) model_.conjunction = TNorm::Minimum;
    if (model_.disjunction == SNorm::None) model_.disjunction = SNorm::Maximum;
    if (model_.implication == TNorm::None) model_.implication = TNorm::Minimum;
    const fuzzy::ModelError e = model_.validate();
    if (e) return fail_at(0, e.message);
    return true;
  }

  bool fail_at(int line, const std::string& message) {
    line_ = line;
    return fail(message);
  }

  Model& model_;
  LoadError& error_;
  const LoadOptions& options_;
  Section section_ = Section::None;
  int line_ = 0;
  bool seen_engine_ = false;
  bool seen_rule_block_ = false;
  int rule_block_line_ = 0;
  std::vector<int> input_lines_;
  std::vector<int> output_lines_;
  std::vector<bool> defuzzifier_seen_;
  std::vector<bool> aggregation_seen_;
};

const char* tnorm_name(TNorm op) {
  return op == TNorm::Minimum ? "Minimum" : op == TNorm::Product ? "AlgebraicProduct" : "none";
}

}  // namespace

bool parse_fll(std::string_view text, const std::string& source, Model& model, LoadError& error,
               const LoadOptions& options) {
  return FllParser(source, model, error, options).parse(text);
}

bool to_fll(const Model& m, std::string& out, std::string& error) {
  const fuzzy::ModelError e = m.validate();
  if (e) {
    error = std::string("invalid model: ") + e.message;
    return false;
  }
  using text::format_number;
  std::string s = "Engine: " + std::string(text::name_of(m.name)) + "\n";
  for (std::size_t i = 0; i < m.num_inputs; ++i) {
    const auto& in = m.inputs[i];
    s += "InputVariable: " + std::string(text::name_of(in.name)) + "\n  enabled: true\n";
    s += "  range: " + format_number(in.min) + " " + format_number(in.max) + "\n";
    s += std::string("  lock-range: ") + (in.lock_range ? "true" : "false") + "\n";
    for (std::size_t t = 0; t < in.num_terms; ++t) {
      const std::string w = terms::write_membership(terms::Format::Fll, in.terms[t]);
      if (w.empty()) {
        error = "input term '" + std::string(text::name_of(in.term_names[t])) +
                "' has a shape .fll cannot express";
        return false;
      }
      s += "  term: " + std::string(text::name_of(in.term_names[t])) + " " + w + "\n";
    }
  }
  for (std::size_t o = 0; o < m.num_outputs; ++o) {
    const auto& out = m.outputs[o];
    const bool sugeno = fuzzy::is_sugeno(out.defuzzifier);
    s += "OutputVariable: " + std::string(text::name_of(out.name)) + "\n  enabled: true\n";
    s += "  range: " + format_number(out.min) + " " + format_number(out.max) + "\n";
    s += std::string("  lock-range: ") + (out.lock_range ? "true" : "false") + "\n";
    s += std::string("  aggregation: ") +
         (sugeno                                           ? "none"
          : out.aggregation == fuzzy::Aggregation::Maximum ? "Maximum"
                                                           : "UnboundedSum") +
         "\n";
    static const char* const names[] = {"Centroid",          "Bisector",         "MeanOfMaximum",
                                        "SmallestOfMaximum", "LargestOfMaximum", "WeightedAverage",
                                        "WeightedSum"};
    s += std::string("  defuzzifier: ") + names[static_cast<int>(out.defuzzifier)] +
         (sugeno ? std::string(" TakagiSugeno") : " " + std::to_string(out.resolution)) + "\n";
    s += "  default: " + format_number(out.default_value) + "\n  lock-previous: false\n";
    for (std::size_t t = 0; t < out.num_terms; ++t) {
      const auto& term = out.terms[t];
      std::string w;
      if (term.kind == fuzzy::OutputTermKind::Constant) {
        w = "Constant " + format_number(term.coefficients[0]);
      } else if (term.kind == fuzzy::OutputTermKind::Linear) {
        w = "Linear";
        for (std::size_t c = 0; c <= m.num_inputs; ++c)
          w += " " + format_number(term.coefficients[c]);
      } else {
        w = terms::write_membership(terms::Format::Fll, term.membership);
      }
      if (w.empty()) {
        error = "output term '" + std::string(text::name_of(out.term_names[t])) +
                "' has a shape .fll cannot express";
        return false;
      }
      s += "  term: " + std::string(text::name_of(out.term_names[t])) + " " + w + "\n";
    }
  }
  s += "RuleBlock: rules\n  enabled: true\n";
  s += std::string("  conjunction: ") + tnorm_name(m.conjunction) + "\n";
  s += std::string("  disjunction: ") +
       (m.disjunction == SNorm::Maximum ? "Maximum" : "AlgebraicSum") + "\n";
  s += std::string("  implication: ") + tnorm_name(m.implication) + "\n  activation: General\n";
  for (std::size_t r = 0; r < m.num_rules; ++r) {
    const auto& rule = m.rules[r];
    std::string line = "  rule: if";
    bool first = true;
    for (std::size_t i = 0; i < m.num_inputs; ++i) {
      const int a = rule.antecedent[i];
      if (a == 0) continue;
      if (!first) line += rule.disjunction ? " or" : " and";
      first = false;
      line += " " + std::string(text::name_of(m.inputs[i].name)) + " is " + (a < 0 ? "not " : "") +
              std::string(text::name_of(
                  m.inputs[i].term_names[static_cast<std::size_t>((a < 0 ? -a : a) - 1)]));
    }
    line += " then";
    first = true;
    for (std::size_t o = 0; o < m.num_outputs; ++o) {
      const int c = rule.consequent[o];
      if (c == 0) continue;
      if (!first) line += " and";
      first = false;
      line += " " + std::string(text::name_of(m.outputs[o].name)) + " is " +
              std::string(text::name_of(m.outputs[o].term_names[static_cast<std::size_t>(c - 1)]));
    }
    if (rule.weight != 1.0) line += " with " + format_number(rule.weight);
    s += line + "\n";
  }
  out = std::move(s);
  return true;
}

}  // namespace fuzzypid::io
