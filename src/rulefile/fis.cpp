// MATLAB Fuzzy Logic Toolbox .fis reader and writer: [System], [InputN], [OutputN] sections of
// Key=Value lines, then [Rules] with one "antecedents, consequents (weight) : connection" line
// per rule. Lines starting with '%' or '#' are comments.
#include <cmath>
#include <map>
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

struct VariableText {
  int line = 0;  // the [InputN] / [OutputN] header
  std::string name;
  int name_line = 0;
  bool has_range = false;
  double min = 0, max = 0;
  std::size_t num_mfs = 0;
  int num_mfs_line = 0;
  bool has_num_mfs = false;
  struct Mf {
    int line = 0;
    std::string name;
    std::string type;
    std::vector<double> params;
  };
  std::map<std::size_t, Mf> mfs;  // by 1-based index
};

class FisParser {
 public:
  FisParser(const std::string& source, Model& model, LoadError& error, const LoadOptions& options)
      : model_(model), error_(error), options_(options) {
    error_ = LoadError{source, 0, {}};
  }

  bool parse(std::string_view text) {
    model_ = Model{};
    enum class Section { None, System, Input, Output, Rules } section = Section::None;
    VariableText* var = nullptr;
    for (const text::Line& line : text::split_lines(text)) {
      line_ = line.number;
      const std::string_view s = text::trim(line.text);
      if (s.empty() || s[0] == '%' || s[0] == '#') continue;
      if (s.front() == '[') {
        if (s.back() != ']') return fail("malformed section header '" + std::string(s) + "'");
        const std::string_view name = s.substr(1, s.size() - 2);
        var = nullptr;
        if (name == "System") {
          if (seen_system_) return fail("duplicate [System] section");
          seen_system_ = true;
          section = Section::System;
        } else if (name == "Rules") {
          if (seen_rules_) return fail("duplicate [Rules] section");
          seen_rules_ = true;
          rules_line_ = line_;
          section = Section::Rules;
        } else if (name.substr(0, 5) == "Input" || name.substr(0, 6) == "Output") {
          const bool input = name[0] == 'I';
          std::size_t index = 0;
          if (!text::parse_count(name.substr(input ? 5 : 6), index) || index < 1)
            return fail("malformed section header '" + std::string(s) + "'");
          if (index > (input ? kMaxInputs : kMaxOutputs))
            return fail(std::string("more than ") + (input ? "8 inputs" : "8 outputs"));
          auto& vars = input ? inputs_ : outputs_;
          if (vars.count(index)) return fail("duplicate section '" + std::string(s) + "'");
          var = &vars[index];
          var->line = line_;
          section = input ? Section::Input : Section::Output;
        } else {
          return fail("unknown section '" + std::string(s) + "'");
        }
        continue;
      }
      switch (section) {
        case Section::None:
          return fail("'" + std::string(s) + "' before any section");
        case Section::System:
          if (!system_entry(s)) return false;
          break;
        case Section::Input:
        case Section::Output:
          if (!variable_entry(*var, s)) return false;
          break;
        case Section::Rules:
          if (!rule_line(s)) return false;
          break;
      }
    }
    return finish();
  }

 private:
  bool fail(const std::string& message) {
    error_.line = line_;
    error_.message = message;
    return false;
  }
  bool fail_at(int line, const std::string& message) {
    line_ = line;
    return fail(message);
  }

  static bool unquote(std::string_view v, std::string& out) {
    if (v.size() < 2 || v.front() != '\'' || v.back() != '\'') return false;
    out = std::string(v.substr(1, v.size() - 2));
    return out.find('\'') == std::string::npos;
  }

  bool split_entry(std::string_view s, std::string_view& key, std::string_view& value) {
    const std::size_t eq = s.find('=');
    if (eq == std::string_view::npos)
      return fail("expected 'Key=Value', got '" + std::string(s) + "'");
    key = text::trim(s.substr(0, eq));
    value = text::trim(s.substr(eq + 1));
    return true;
  }

  bool system_entry(std::string_view s) {
    std::string_view key, value;
    if (!split_entry(s, key, value)) return false;
    std::string str;
    const auto quoted = [&](const char* what) {
      if (!unquote(value, str)) return fail(std::string(what) + " must be a quoted string");
      return true;
    };
    const auto count = [&](std::size_t& n, int& at) {
      if (!text::parse_count(value, n))
        return fail(std::string(key) + " must be a non-negative integer, got '" +
                    std::string(value) + "'");
      at = line_;
      return true;
    };
    if (key == "Name") {
      if (!quoted("Name")) return false;
      if (!fuzzy::set_name(model_.name, str.data(), str.size()))
        return fail("system name longer than 31 bytes");
      return true;
    }
    if (key == "Type") {
      if (!quoted("Type")) return false;
      if (str != "mamdani" && str != "sugeno")
        return fail("unsupported system type '" + str + "' (mamdani or sugeno)");
      type_ = str;
      type_line_ = line_;
      return true;
    }
    if (key == "Version") return true;
    if (key == "NumInputs") return count(num_inputs_, num_inputs_line_) && (has_inputs_ = true);
    if (key == "NumOutputs") return count(num_outputs_, num_outputs_line_) && (has_outputs_ = true);
    if (key == "NumRules") return count(num_rules_, num_rules_line_) && (has_rules_ = true);
    if (key == "AndMethod" || key == "ImpMethod") {
      if (!quoted(key == "AndMethod" ? "AndMethod" : "ImpMethod")) return false;
      TNorm& op = key == "AndMethod" ? model_.conjunction : model_.implication;
      if (str == "min") {
        op = TNorm::Minimum;
      } else if (str == "prod") {
        op = TNorm::Product;
      } else {
        return fail("unsupported " + std::string(key) + " '" + str + "' (min or prod)");
      }
      return true;
    }
    if (key == "OrMethod") {
      if (!quoted("OrMethod")) return false;
      if (str == "max") {
        model_.disjunction = SNorm::Maximum;
      } else if (str == "probor") {
        model_.disjunction = SNorm::ProbabilisticSum;
      } else {
        return fail("unsupported OrMethod '" + str + "' (max or probor)");
      }
      return true;
    }
    if (key == "AggMethod") {
      if (!quoted("AggMethod")) return false;
      if (str == "max") {
        aggregation_ = fuzzy::Aggregation::Maximum;
      } else if (str == "sum") {
        aggregation_ = fuzzy::Aggregation::Sum;
      } else {
        return fail("unsupported AggMethod '" + str + "' (max or sum)");
      }
      return true;
    }
    if (key == "DefuzzMethod") {
      if (!quoted("DefuzzMethod")) return false;
      static const std::pair<const char*, Defuzzifier> names[] = {
          {"centroid", Defuzzifier::Centroid},    {"bisector", Defuzzifier::Bisector},
          {"mom", Defuzzifier::MeanOfMaximum},    {"som", Defuzzifier::SmallestOfMaximum},
          {"lom", Defuzzifier::LargestOfMaximum}, {"wtaver", Defuzzifier::WeightedAverage},
          {"wtsum", Defuzzifier::WeightedSum}};
      for (const auto& n : names) {
        if (str == n.first) {
          defuzzifier_ = n.second;
          defuzz_line_ = line_;
          has_defuzz_ = true;
          return true;
        }
      }
      return fail("unsupported DefuzzMethod '" + str + "'");
    }
    return fail("unknown [System] key '" + std::string(key) + "'");
  }

  bool variable_entry(VariableText& v, std::string_view s) {
    std::string_view key, value;
    if (!split_entry(s, key, value)) return false;
    if (key == "Name") {
      if (!unquote(value, v.name)) return fail("Name must be a quoted string");
      v.name_line = line_;
      return true;
    }
    if (key == "Range") {
      if (value.size() < 2 || value.front() != '[' || value.back() != ']')
        return fail("Range must be [min max]");
      const auto words = split_list(value.substr(1, value.size() - 2));
      if (words.size() != 2 || !text::parse_number(words[0], v.min) ||
          !text::parse_number(words[1], v.max))
        return fail("Range must hold two numbers, got '" + std::string(value) + "'");
      if (!(std::isfinite(v.min) && std::isfinite(v.max) && v.min < v.max))
        return fail("Range must be finite with min < max, got '" + std::string(value) + "'");
      v.has_range = true;
      return true;
    }
    if (key == "NumMFs") {
      if (!text::parse_count(value, v.num_mfs))
        return fail("NumMFs must be a non-negative integer");
      v.num_mfs_line = line_;
      v.has_num_mfs = true;
      return true;
    }
    if (key.substr(0, 2) == "MF") {
      std::size_t index = 0;
      if (!text::parse_count(key.substr(2), index) || index < 1)
        return fail("malformed key '" + std::string(key) + "'");
      if (index > kMaxTerms) return fail("more than 16 membership functions");
      if (v.mfs.count(index)) return fail("duplicate " + std::string(key));
      // 'name':'type',[p1 p2 ...]
      VariableText::Mf mf;
      mf.line = line_;
      const std::size_t colon = value.find("':'");
      const std::size_t comma = value.find("',[");
      if (colon == std::string_view::npos || comma == std::string_view::npos || comma < colon ||
          value.front() != '\'' || value.back() != ']')
        return fail("expected MFk='name':'type',[params], got '" + std::string(value) + "'");
      mf.name = std::string(value.substr(1, colon - 1));
      mf.type = std::string(value.substr(colon + 3, comma - colon - 3));
      for (std::string_view word : split_list(value.substr(comma + 3, value.size() - comma - 4))) {
        double x = 0;
        if (!text::parse_number(word, x, true))
          return fail(std::string(key) + ": '" + std::string(word) + "' is not a number");
        mf.params.push_back(x);
      }
      v.mfs[index] = mf;
      return true;
    }
    return fail("unknown variable key '" + std::string(key) + "'");
  }

  static std::vector<std::string_view> split_list(std::string_view s) {
    std::vector<std::string_view> out;
    std::size_t k = 0;
    while (k < s.size()) {
      while (k < s.size() && (s[k] == ' ' || s[k] == '\t' || s[k] == ','))
        ++k;
      const std::size_t b = k;
      while (k < s.size() && s[k] != ' ' && s[k] != '\t' && s[k] != ',')
        ++k;
      if (k > b) out.push_back(s.substr(b, k - b));
    }
    return out;
  }

  bool integer(std::string_view word, int& value) {
    double x = 0;
    if (!text::parse_number(word, x) || std::floor(x) != x || std::fabs(x) > 1000) return false;
    value = static_cast<int>(x);
    return true;
  }

  bool rule_line(std::string_view s) {
    RuleText r;
    r.line = line_;
    const std::size_t comma = s.find(',');
    const std::size_t open = s.find('(');
    const std::size_t close = s.find(')');
    const std::size_t colon = s.find(':');
    if (comma == std::string_view::npos || open == std::string_view::npos ||
        close == std::string_view::npos || colon == std::string_view::npos ||
        !(comma < open && open < close && close < colon))
      return fail("expected 'i1 i2 ..., o1 o2 ... (weight) : connection', got '" + std::string(s) +
                  "'");
    for (std::string_view w : text::split_words(s.substr(0, comma))) {
      int v = 0;
      if (!integer(w, v)) return fail("rule antecedent '" + std::string(w) + "' is not an integer");
      r.antecedent.push_back(v);
    }
    for (std::string_view w : text::split_words(s.substr(comma + 1, open - comma - 1))) {
      int v = 0;
      if (!integer(w, v)) return fail("rule consequent '" + std::string(w) + "' is not an integer");
      r.consequent.push_back(v);
    }
    if (!text::parse_number(text::trim(s.substr(open + 1, close - open - 1)), r.weight) ||
        !(r.weight >= 0 && r.weight <= 1))
      return fail("rule weight must be a number in [0, 1]");
    if (!text::trim(s.substr(close + 1, colon - close - 1)).empty())
      return fail("unexpected text between ')' and ':'");
    int connection = 0;
    if (!integer(text::trim(s.substr(colon + 1)), connection) ||
        (connection != 1 && connection != 2))
      return fail("rule connection must be 1 (and) or 2 (or)");
    r.disjunction = connection == 2;
    if (rules_.size() == kMaxRules) return fail("more than 512 rules");
    rules_.push_back(r);
    return true;
  }

  bool build_variable(const VariableText& v, bool input, std::size_t index) {
    const std::string what = (input ? "[Input" : "[Output") + std::to_string(index) + "]";
    if (v.name.empty()) return fail_at(v.line, what + " has no Name");
    if (!text::valid_identifier(v.name))
      return fail_at(v.name_line,
                     "variable name '" + v.name +
                         "' must be letters, digits, '_' or '.' and not a rule keyword");
    if (v.name.size() > fuzzy::kMaxNameLength)
      return fail_at(v.name_line, "variable name longer than 31 bytes");
    if (!names_.insert({v.name, v.name_line}).second)
      return fail_at(v.name_line, "duplicate variable name '" + v.name + "'");
    if (!v.has_range) return fail_at(v.line, what + " has no Range");
    if (!v.has_num_mfs) return fail_at(v.line, what + " has no NumMFs");
    if (v.num_mfs < 1) return fail_at(v.num_mfs_line, "NumMFs must be at least 1");
    if (v.num_mfs > kMaxTerms) return fail_at(v.num_mfs_line, "more than 16 membership functions");
    if (v.mfs.size() != v.num_mfs || (!v.mfs.empty() && v.mfs.rbegin()->first != v.num_mfs))
      return fail_at(v.num_mfs_line, "NumMFs=" + std::to_string(v.num_mfs) + " but " +
                                         std::to_string(v.mfs.size()) +
                                         " MF lines (numbered 1..NumMFs) follow");
    const bool sugeno = type_ == "sugeno";
    std::map<std::string, int> term_names;
    for (const auto& [k, mf] : v.mfs) {
      if (!text::valid_identifier(mf.name))
        return fail_at(mf.line, "term name '" + mf.name +
                                    "' must be letters, digits, '_' or '.' and not a rule keyword");
      if (mf.name.size() > fuzzy::kMaxNameLength)
        return fail_at(mf.line, "term name longer than 31 bytes");
      if (!term_names.insert({mf.name, mf.line}).second)
        return fail_at(mf.line, "duplicate term name '" + mf.name + "'");
      const std::size_t t = k - 1;
      std::string why;
      if (input) {
        auto& in = model_.inputs[index - 1];
        why = terms::make_membership(terms::Format::Fis, mf.type, mf.params, in.terms[t]);
        (void)fuzzy::set_name(in.term_names[t], mf.name.data(), mf.name.size());
      } else {
        auto& out = model_.outputs[index - 1];
        auto& term = out.terms[t];
        (void)fuzzy::set_name(out.term_names[t], mf.name.data(), mf.name.size());
        if (sugeno) {
          for (double x : mf.params)
            if (!std::isfinite(x)) why = "coefficients must be finite";
          if (!why.empty()) {
          } else if (mf.type == "constant") {
            if (mf.params.size() != 1) why = "'constant' takes 1 parameter";
            term.kind = fuzzy::OutputTermKind::Constant;
            if (why.empty()) term.coefficients[0] = mf.params[0];
          } else if (mf.type == "linear") {
            if (mf.params.size() != num_inputs_ + 1)
              why = "'linear' takes NumInputs + 1 = " + std::to_string(num_inputs_ + 1) +
                    " parameters, got " + std::to_string(mf.params.size());
            term.kind = fuzzy::OutputTermKind::Linear;
            for (std::size_t c = 0; why.empty() && c < mf.params.size(); ++c)
              term.coefficients[c] = mf.params[c];
          } else {
            why = "a sugeno output needs 'constant' or 'linear' terms, not '" + mf.type + "'";
          }
        } else {
          term.kind = fuzzy::OutputTermKind::Membership;
          why = terms::make_membership(terms::Format::Fis, mf.type, mf.params, term.membership);
          if (why.empty() && options_.exact_centroid && defuzzifier_ == Defuzzifier::Centroid &&
              !fuzzy::is_piecewise_linear(term.membership))
            why = "'" + mf.type + "' is not piecewise linear (exact centroid requested)";
        }
      }
      if (!why.empty())
        return fail_at(mf.line, "MF" + std::to_string(k) + " '" + mf.name + "': " + why);
    }
    if (input) {
      auto& in = model_.inputs[index - 1];
      (void)fuzzy::set_name(in.name, v.name.data(), v.name.size());
      in.min = v.min;
      in.max = v.max;
      in.num_terms = v.num_mfs;
    } else {
      auto& out = model_.outputs[index - 1];
      (void)fuzzy::set_name(out.name, v.name.data(), v.name.size());
      out.min = v.min;
      out.max = v.max;
      out.num_terms = v.num_mfs;
      out.defuzzifier = defuzzifier_;
      out.aggregation = aggregation_;
      out.resolution = options_.fis_resolution;
      out.exact_centroid = options_.exact_centroid;
    }
    return true;
  }

  bool finish() {
    if (!seen_system_) return fail_at(0, "missing [System] section");
    if (type_.empty()) return fail_at(0, "[System] has no Type");
    if (!has_inputs_ || !has_outputs_ || !has_rules_)
      return fail_at(0, "[System] needs NumInputs, NumOutputs and NumRules");
    if (!has_defuzz_) return fail_at(0, "[System] has no DefuzzMethod");
    const bool sugeno = type_ == "sugeno";
    if (sugeno != fuzzy::is_sugeno(defuzzifier_))
      return fail_at(defuzz_line_, "DefuzzMethod does not fit Type='" + type_ + "'");
    if (num_inputs_ < 1 || num_inputs_ > kMaxInputs)
      return fail_at(num_inputs_line_, "NumInputs must be in 1..8");
    if (num_outputs_ < 1 || num_outputs_ > kMaxOutputs)
      return fail_at(num_outputs_line_, "NumOutputs must be in 1..8");
    if (num_rules_ > kMaxRules) return fail_at(num_rules_line_, "NumRules must be at most 512");
    if (options_.fis_resolution < 1) return fail_at(0, "LoadOptions::fis_resolution must be >= 1");
    model_.num_inputs = num_inputs_;
    model_.num_outputs = num_outputs_;
    for (std::size_t i = 1; i <= num_inputs_; ++i) {
      const auto it = inputs_.find(i);
      if (it == inputs_.end())
        return fail_at(num_inputs_line_, "NumInputs=" + std::to_string(num_inputs_) +
                                             " but [Input" + std::to_string(i) + "] is missing");
      if (!build_variable(it->second, true, i)) return false;
    }
    if (inputs_.size() != num_inputs_)
      return fail_at(inputs_.rbegin()->second.line, "more [InputN] sections than NumInputs");
    for (std::size_t o = 1; o <= num_outputs_; ++o) {
      const auto it = outputs_.find(o);
      if (it == outputs_.end())
        return fail_at(num_outputs_line_, "NumOutputs=" + std::to_string(num_outputs_) +
                                              " but [Output" + std::to_string(o) + "] is missing");
      if (!build_variable(it->second, false, o)) return false;
    }
    if (outputs_.size() != num_outputs_)
      return fail_at(outputs_.rbegin()->second.line, "more [OutputN] sections than NumOutputs");
    if (!seen_rules_) return fail_at(0, "missing [Rules] section");
    if (rules_.size() != num_rules_)
      return fail_at(num_rules_line_, "NumRules=" + std::to_string(num_rules_) + " but " +
                                          std::to_string(rules_.size()) + " rules follow");
    for (std::size_t r = 0; r < rules_.size(); ++r) {
      const RuleText& rt = rules_[r];
      line_ = rt.line;
      if (rt.antecedent.size() != num_inputs_)
        return fail("rule has " + std::to_string(rt.antecedent.size()) +
                    " antecedent indices, NumInputs is " + std::to_string(num_inputs_));
      if (rt.consequent.size() != num_outputs_)
        return fail("rule has " + std::to_string(rt.consequent.size()) +
                    " consequent indices, NumOutputs is " + std::to_string(num_outputs_));
      fuzzy::Rule<double> rule;
      std::size_t antecedents = 0, consequents = 0;
      for (std::size_t i = 0; i < num_inputs_; ++i) {
        const int a = rt.antecedent[i];
        if (std::abs(a) > static_cast<int>(model_.inputs[i].num_terms))
          return fail("rule names term " + std::to_string(a) + " of input " +
                      std::to_string(i + 1) + ", which has " +
                      std::to_string(model_.inputs[i].num_terms));
        rule.antecedent[i] = static_cast<std::int8_t>(a);
        antecedents += a != 0;
      }
      for (std::size_t o = 0; o < num_outputs_; ++o) {
        const int c = rt.consequent[o];
        if (c < 0) return fail("negated consequents are not supported");
        if (c > static_cast<int>(model_.outputs[o].num_terms))
          return fail("rule names term " + std::to_string(c) + " of output " +
                      std::to_string(o + 1) + ", which has " +
                      std::to_string(model_.outputs[o].num_terms));
        rule.consequent[o] = static_cast<std::int8_t>(c);
        consequents += c != 0;
      }
      if (antecedents == 0) return fail("rule has no antecedent (all indices 0)");
      if (consequents == 0) return fail("rule has no consequent (all indices 0)");
      rule.weight = rt.weight;
      rule.disjunction = rt.disjunction;
      model_.rules[r] = rule;
    }
    model_.num_rules = rules_.size();
    const fuzzy::ModelError e = model_.validate();
    if (e) return fail_at(0, e.message);
    return true;
  }

  struct RuleText {
    int line = 0;
    std::vector<int> antecedent;
    std::vector<int> consequent;
    double weight = 1;
    bool disjunction = false;
  };

  Model& model_;
  LoadError& error_;
  const LoadOptions& options_;
  int line_ = 0;
  bool seen_system_ = false;
  bool seen_rules_ = false;
  int rules_line_ = 0;
  std::string type_;
  int type_line_ = 0;
  std::size_t num_inputs_ = 0, num_outputs_ = 0, num_rules_ = 0;
  int num_inputs_line_ = 0, num_outputs_line_ = 0, num_rules_line_ = 0;
  bool has_inputs_ = false, has_outputs_ = false, has_rules_ = false, has_defuzz_ = false;
  Defuzzifier defuzzifier_ = Defuzzifier::Centroid;
  int defuzz_line_ = 0;
  fuzzy::Aggregation aggregation_ = fuzzy::Aggregation::Maximum;
  std::map<std::size_t, VariableText> inputs_;
  std::map<std::size_t, VariableText> outputs_;
  std::map<std::string, int> names_;
  std::vector<RuleText> rules_;
};

}  // namespace

bool parse_fis(std::string_view text, const std::string& source, Model& model, LoadError& error,
               const LoadOptions& options) {
  return FisParser(source, model, error, options).parse(text);
}

bool to_fis(const Model& m, std::string& out, std::string& error) {
  const fuzzy::ModelError e = m.validate();
  if (e) {
    error = std::string("invalid model: ") + e.message;
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
    if (v.lock_range || v.default_value == v.default_value) {
      error = "output '" + std::string(text::name_of(v.name)) +
              "' has lock-range or a default value, which .fis cannot express";
      return false;
    }
  }
  for (std::size_t i = 0; i < m.num_inputs; ++i) {
    if (m.inputs[i].lock_range) {
      error = "input '" + std::string(text::name_of(m.inputs[i].name)) +
              "' has lock-range, which .fis cannot express";
      return false;
    }
  }
  using text::format_number;
  const bool sugeno = fuzzy::is_sugeno(first.defuzzifier);
  static const char* const defuzz[] = {"centroid", "bisector", "mom",  "som",
                                       "lom",      "wtaver",   "wtsum"};
  std::string s = "[System]\n";
  s += "Name=" + text::quoted(text::name_of(m.name)) + "\n";
  s += std::string("Type='") + (sugeno ? "sugeno" : "mamdani") + "'\nVersion=2.0\n";
  s += "NumInputs=" + std::to_string(m.num_inputs) + "\n";
  s += "NumOutputs=" + std::to_string(m.num_outputs) + "\n";
  s += "NumRules=" + std::to_string(m.num_rules) + "\n";
  s += std::string("AndMethod='") + (m.conjunction == TNorm::Product ? "prod" : "min") + "'\n";
  s += std::string("OrMethod='") + (m.disjunction == SNorm::ProbabilisticSum ? "probor" : "max") +
       "'\n";
  s += std::string("ImpMethod='") + (m.implication == TNorm::Product ? "prod" : "min") + "'\n";
  s += std::string("AggMethod='") + (first.aggregation == fuzzy::Aggregation::Sum ? "sum" : "max") +
       "'\n";
  s += std::string("DefuzzMethod='") + defuzz[static_cast<int>(first.defuzzifier)] + "'\n";
  const auto variable = [&](const char* kind, std::size_t index, const fuzzy::Name& name, double lo,
                            double hi, std::size_t n) {
    s += "\n[" + std::string(kind) + std::to_string(index + 1) + "]\n";
    s += "Name=" + text::quoted(text::name_of(name)) + "\n";
    s += "Range=[" + format_number(lo) + " " + format_number(hi) + "]\n";
    s += "NumMFs=" + std::to_string(n) + "\n";
  };
  for (std::size_t i = 0; i < m.num_inputs; ++i) {
    const auto& in = m.inputs[i];
    variable("Input", i, in.name, in.min, in.max, in.num_terms);
    for (std::size_t t = 0; t < in.num_terms; ++t) {
      const std::string w = terms::write_membership(terms::Format::Fis, in.terms[t]);
      if (w.empty()) {
        error = "input term '" + std::string(text::name_of(in.term_names[t])) +
                "' has a shape .fis cannot express";
        return false;
      }
      s += "MF" + std::to_string(t + 1) + "=" + text::quoted(text::name_of(in.term_names[t])) +
           ":" + w + "\n";
    }
  }
  for (std::size_t o = 0; o < m.num_outputs; ++o) {
    const auto& v = m.outputs[o];
    variable("Output", o, v.name, v.min, v.max, v.num_terms);
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
        w = terms::write_membership(terms::Format::Fis, term.membership);
      }
      if (w.empty()) {
        error = "output term '" + std::string(text::name_of(v.term_names[t])) +
                "' has a shape .fis cannot express";
        return false;
      }
      s += "MF" + std::to_string(t + 1) + "=" + text::quoted(text::name_of(v.term_names[t])) + ":" +
           w + "\n";
    }
  }
  s += "\n[Rules]\n";
  for (std::size_t r = 0; r < m.num_rules; ++r) {
    const auto& rule = m.rules[r];
    std::string line;
    for (std::size_t i = 0; i < m.num_inputs; ++i)
      line += (i ? " " : "") + std::to_string(rule.antecedent[i]);
    line += ",";
    for (std::size_t o = 0; o < m.num_outputs; ++o)
      line += " " + std::to_string(rule.consequent[o]);
    line += " (" + format_number(rule.weight) + ") : " + (rule.disjunction ? "2" : "1");
    s += line + "\n";
  }
  out = std::move(s);
  return true;
}

}  // namespace fuzzypid::io
