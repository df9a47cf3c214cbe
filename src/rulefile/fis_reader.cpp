// MATLAB Fuzzy Logic Toolbox .fis reader (fis_writer.cpp writes the format): [System], [InputN],
// [OutputN] sections of Key=Value lines, then [Rules] with one "antecedents, consequents (weight)
// : connection" line per rule. Lines starting with '%' or '#' are comments; spaces may surround
// every delimiter (as Octave and MATLAB write them).
//
// MF lines are taken in line order, as MATLAB's readfis and fuzzylite do: the k of `MFk=` must be
// a distinct number in 1..NumMFs but does not reorder the terms (a file listing MF2 before MF1
// means what MATLAB reads).
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "check.hpp"
#include "fuzzypid/rulefile/rule_file.hpp"
#include "rules.hpp"
#include "terms.hpp"
#include "text.hpp"

namespace fuzzypid::rulefile {

namespace {

using fuzzy::Conclusion;
using fuzzy::Defuzzifier;
using fuzzy::Hedge;
using fuzzy::SNorm;
using fuzzy::TNorm;
using fuzzy::Token;
using Cap = Builder::Capacity;

struct VariableText {
  int line = 0;  // the [InputN] / [OutputN] header
  std::string name;
  int name_line = 0;
  bool has_range = false;
  double min = 0, max = 0;
  std::size_t num_mfs = 0;
  int num_mfs_line = 0;
  bool has_num_mfs = false;
  // The keys fuzzylite's FisExporter writes (outputs: Default, LockPrevious, LockRange).
  bool lock_range = false, lock_previous = false;
  bool enabled = true;  // Enabled=0: a disabled variable (fuzzylite's export)
  double default_value = std::numeric_limits<double>::quiet_NaN();
  struct Mf {
    int line = 0;
    std::size_t k = 0;
    std::string name;
    std::string type;
    std::vector<double> params;
  };
  std::vector<Mf> mfs;  // in line order
};

// A small scanner over one value: quoted strings, punctuation, bracketed lists.
class Scanner {
 public:
  explicit Scanner(std::string_view s) : s_(s) {}
  void skip() {
    while (k_ < s_.size() && (s_[k_] == ' ' || s_[k_] == '\t'))
      ++k_;
  }
  bool quoted(std::string& out) {
    skip();
    if (k_ >= s_.size() || s_[k_] != '\'') return false;
    const std::size_t end = s_.find('\'', k_ + 1);
    if (end == std::string_view::npos) return false;
    out = std::string(s_.substr(k_ + 1, end - k_ - 1));
    // Control characters (NUL, line breaks, ...) are no part of a name any writer produces, and
    // no format could write them back: refuse them here.
    for (const char c : out)
      if (static_cast<unsigned char>(c) < 0x20 || c == '\x7f') return false;
    k_ = end + 1;
    return true;
  }
  bool punct(char c) {
    skip();
    if (k_ >= s_.size() || s_[k_] != c) return false;
    ++k_;
    return true;
  }
  // "[ a b, c ]" -> words
  bool list(std::vector<std::string_view>& out) {
    skip();
    if (k_ >= s_.size() || s_[k_] != '[') return false;
    const std::size_t end = s_.find(']', k_);
    if (end == std::string_view::npos) return false;
    std::string_view inner = s_.substr(k_ + 1, end - k_ - 1);
    k_ = end + 1;
    std::size_t j = 0;
    while (j < inner.size()) {
      while (j < inner.size() && (inner[j] == ' ' || inner[j] == '\t' || inner[j] == ','))
        ++j;
      const std::size_t b = j;
      while (j < inner.size() && inner[j] != ' ' && inner[j] != '\t' && inner[j] != ',')
        ++j;
      if (j > b) out.push_back(inner.substr(b, j - b));
    }
    return true;
  }
  bool at_end() {
    skip();
    return k_ == s_.size();
  }

 private:
  std::string_view s_;
  std::size_t k_ = 0;
};

class FisParser {
 public:
  FisParser(const std::string& source, Builder& model, LoadError& error, const LoadOptions& options)
      : model_(model), error_(error), options_(options) {
    error_ = LoadError{source, 0, {}, {}};
  }

  bool parse(std::string_view text) {
    model_ = Builder{};
    enum class Section { None, System, Input, Output, Rules } section = Section::None;
    VariableText* var = nullptr;
    for (const text::Line& line : text::split_lines(text)) {
      line_ = line.number;
      const std::string_view s = text::trim(line.text);
      if (s.empty() || s[0] == '%' || s[0] == '#') continue;
      if (s.front() == '[' && section != Section::Rules) {
        if (s.back() != ']') return fail("malformed section header '" + std::string(s) + "'");
        const std::string_view name = text::trim(s.substr(1, s.size() - 2));
        var = nullptr;
        if (name == "System") {
          if (seen_system_) return fail("duplicate [System] section");
          seen_system_ = true;
          section = Section::System;
        } else if (name == "Rules") {
          if (seen_rules_) return fail("duplicate [Rules] section");
          seen_rules_ = true;
          section = Section::Rules;
        } else if (name.substr(0, 5) == "Input" || name.substr(0, 6) == "Output") {
          const bool input = name[0] == 'I';
          std::size_t index = 0;
          if (!text::parse_count(name.substr(input ? 5 : 6), index) || index < 1)
            return fail("malformed section header '" + std::string(s) + "'");
          if (index > (input ? Cap::inputs : Cap::outputs))
            return fail(std::string("more ") + (input ? "inputs" : "outputs") +
                        " than the capacity (" + capacity_text() + ")");
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
      if (s == "[Rules]") return fail("duplicate [Rules] section");
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

  bool split_entry(std::string_view s, std::string_view& key, std::string_view& value) {
    const std::size_t eq = s.find('=');
    if (eq == std::string_view::npos)
      return fail("expected 'Key=Value', got '" + std::string(s) + "'");
    key = text::trim(s.substr(0, eq));
    value = text::trim(s.substr(eq + 1));
    return true;
  }

  bool quoted_value(std::string_view key, std::string_view value, std::string& out) {
    Scanner sc(value);
    if (!sc.quoted(out) || !sc.at_end())
      return fail(std::string(key) + " must be a quoted string, got '" + std::string(value) + "'");
    return true;
  }

  bool system_entry(std::string_view s) {
    std::string_view key, value;
    if (!split_entry(s, key, value)) return false;
    std::string str;
    const auto count = [&](std::size_t& n, int& at) {
      if (!text::parse_count(value, n))
        return fail(std::string(key) + " must be a non-negative integer, got '" +
                    std::string(value) + "'");
      at = line_;
      return true;
    };
    if (key == "Name") {
      if (!quoted_value(key, value, str)) return false;
      if (!fuzzy::set_name(model_.name, str.data(), str.size()))
        return fail("system name longer than 31 bytes");
      return true;
    }
    if (key == "Type") {
      if (!quoted_value(key, value, str)) return false;
      // hybrid and tsukamoto: as fuzzylite writes them (Mamdani and Sugeno outputs side by side;
      // weighted defuzzifiers over monotonic terms).
      if (str != "mamdani" && str != "sugeno" && str != "hybrid" && str != "tsukamoto")
        return fail("unsupported system Type '" + str + "' (mamdani, sugeno, hybrid, tsukamoto)");
      type_ = str;
      return true;
    }
    if (key == "Version" || key == "DisableStructuralChecks") return true;
    if (key == "NumInputs") return count(num_inputs_, num_inputs_line_) && (has_inputs_ = true);
    if (key == "NumOutputs") return count(num_outputs_, num_outputs_line_) && (has_outputs_ = true);
    if (key == "NumRules") return count(num_rules_, num_rules_line_) && (has_rules_ = true);
    // An empty method ('') is no operator, as fuzzylite reads it: refused later only where a rule
    // or output needs it (EngineModel::validate, placed on that rule's or output's line).
    if (key == "AndMethod" || key == "ImpMethod") {
      if (!quoted_value(key, value, str)) return false;
      const bool conj = key == "AndMethod";
      TNorm& op = conj ? block_.conjunction : block_.implication;
      (conj ? block_.has_conjunction : block_.has_implication) = !str.empty();
      if (!str.empty() && !fuzzy::parse(str, fuzzy::Naming::Fis, op))
        return fail("unsupported " + std::string(key) + " '" + str + "'");
      return true;
    }
    if (key == "OrMethod") {
      if (!quoted_value(key, value, str)) return false;
      block_.has_disjunction = !str.empty();
      if (!str.empty() && !fuzzy::parse(str, fuzzy::Naming::Fis, block_.disjunction))
        return fail("unsupported OrMethod '" + str + "'");
      return true;
    }
    if (key == "AggMethod") {
      if (!quoted_value(key, value, str)) return false;
      has_aggregation_ = !str.empty();
      agg_line_ = line_;
      if (!str.empty() && !fuzzy::parse(str, fuzzy::Naming::Fis, aggregation_))
        return fail("unsupported AggMethod '" + str + "'");
      return true;
    }
    if (key == "DefuzzMethod") {
      if (!quoted_value(key, value, str)) return false;
      if (!fuzzy::parse(str, fuzzy::Naming::Fis, defuzzifier_))
        return fail("unsupported DefuzzMethod '" + str + "'");
      defuzz_line_ = line_;
      has_defuzz_ = true;
      return true;
    }
    return fail("unknown [System] key '" + std::string(key) + "'");
  }

  bool variable_entry(VariableText& v, std::string_view s) {
    std::string_view key, value;
    if (!split_entry(s, key, value)) return false;
    if (key == "Name") {
      if (!quoted_value(key, value, v.name)) return false;
      v.name_line = line_;
      return true;
    }
    if (key == "Range") {
      // MATLAB evaluates the bounds: numbers or constant expressions (`[-pi/4 pi/4]`).
      const std::string_view trimmed = text::trim(value);
      if (trimmed.size() < 2 || trimmed.front() != '[' || trimmed.back() != ']' ||
          trimmed.find(']') != trimmed.size() - 1)
        return fail("Range must be [min max], got '" + std::string(value) + "'");
      const auto bounds = text::matlab_row_elements(trimmed.substr(1, trimmed.size() - 2));
      if (bounds.size() != 2)
        return fail("Range must hold two numbers, got '" + std::string(value) + "'");
      for (std::size_t k = 0; k < 2; ++k) {
        double& bound = k == 0 ? v.min : v.max;
        std::string why;
        if (!text::parse_number(bounds[k], bound) &&
            !text::evaluate_matlab_constant(bounds[k], bound, why))
          return fail("Range must hold two numbers or constant expressions, got '" +
                      std::string(bounds[k]) + "' (" + why + ")");
      }
      // min == max is allowed where the range is unused (Sugeno outputs; EngineModel::validate).
      if (!(std::isfinite(v.min) && std::isfinite(v.max) && v.min <= v.max))
        return fail("Range must be finite with min < max, got '" + std::string(value) + "'");
      v.has_range = true;
      return true;
    }
    if (key == "Enabled" || key == "LockPrevious" || key == "LockRange") {
      double flag = 0;
      if (!text::parse_number(value, flag) || !(flag == 0 || flag == 1))
        return fail(std::string(key) + " must be 0 or 1, got '" + std::string(value) + "'");
      (key == "Enabled"     ? v.enabled
       : key == "LockRange" ? v.lock_range
                            : v.lock_previous) = flag == 1;
      return true;
    }
    if (key == "Default") {
      if (!text::parse_number(value, v.default_value, true) || std::isinf(v.default_value))
        return fail("Default must be a finite number or nan, got '" + std::string(value) + "'");
      return true;
    }
    if (key == "NumMFs") {
      if (!text::parse_count(value, v.num_mfs))
        return fail("NumMFs must be a non-negative integer, got '" + std::string(value) + "'");
      v.num_mfs_line = line_;
      v.has_num_mfs = true;
      return true;
    }
    if (key.substr(0, 2) == "MF") {
      VariableText::Mf mf;
      if (!text::parse_count(key.substr(2), mf.k) || mf.k < 1)
        return fail("malformed key '" + std::string(key) + "'");
      // 'name' : 'type' , [p1 p2 ...]
      mf.line = line_;
      Scanner sc(value);
      std::vector<std::string_view> words;
      if (!sc.quoted(mf.name) || !sc.punct(':') || !sc.quoted(mf.type) || !sc.punct(',') ||
          !sc.list(words) || !sc.at_end())
        return fail("expected " + std::string(key) + "='name':'type',[params], got '" +
                    std::string(value) + "'");
      for (std::string_view word : words) {
        double x = 0;
        if (!text::parse_number(word, x, true)) {
          if (mf.type == "function") return fail(std::string(terms::kFisFunction));
          return fail(std::string(key) + " '" + mf.name + "': '" + std::string(word) +
                      "' is not a number");
        }
        mf.params.push_back(x);
      }
      v.mfs.push_back(mf);
      return true;
    }
    return fail("unknown variable key '" + std::string(key) + "'");
  }

  bool integer_code(std::string_view word, double& value) {
    return text::parse_number(word, value) && std::fabs(value) < 1000;
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
      double v = 0;
      if (!integer_code(w, v))
        return fail("rule antecedent '" + std::string(w) + "' is not a number");
      r.antecedent.push_back(v);
    }
    for (std::string_view w : text::split_words(s.substr(comma + 1, open - comma - 1))) {
      double v = 0;
      if (!integer_code(w, v))
        return fail("rule consequent '" + std::string(w) + "' is not a number");
      r.consequent.push_back(v);
    }
    if (!text::parse_number(text::trim(s.substr(open + 1, close - open - 1)), r.weight) ||
        !(r.weight >= 0 && r.weight <= 1))
      return fail("rule weight must be a number in [0, 1]");
    if (!text::trim(s.substr(close + 1, colon - close - 1)).empty())
      return fail("unexpected text between ')' and ':'");
    std::size_t connection = 0;
    if (!text::parse_count(text::trim(s.substr(colon + 1)), connection) ||
        (connection != 1 && connection != 2))
      return fail("rule connection must be 1 (and) or 2 (or), got '" +
                  std::string(text::trim(s.substr(colon + 1))) + "'");
    r.disjunction = connection == 2;
    if (rules_.size() == Cap::rules)
      return fail("more rules than the capacity (" + capacity_text() + ")");
    rules_.push_back(r);
    return true;
  }

  // A rule's index code as Octave's fuzzy-logic-toolkit reads it (get_mf_index_and_hedge): sign =
  // not, integer part = term (0 = none), fraction .dd = hedge, the degree raised to dd/10 (dd =
  // round(100 * fraction), 1..100; MATLAB has no hedges). Where that power is one of fuzzylite's
  // hedges it is written as one: .05 somewhat (mu^0.5), .2 very (mu^2), .4 very very (mu^4); the
  // others (.3 = mu^3, .01 = mu^0.1, ...) are Octave's power hedge. On a conclusion every .dd is
  // the power hedge, Octave's w^(1 / (dd/10)) (Sugeno outputs only). 0.99 without a term is
  // fuzzylite's `any` (its FisExporter's extension; Octave reads a degree of 0).
  bool decode(double code, std::size_t index, std::size_t num_terms, int& term, Token& t,
              bool output) {
    const double a = std::fabs(code);
    const double whole = std::floor(a);
    const double frac = a - whole;
    term = static_cast<int>(whole) - 1;
    t.num_hedges = 0;
    t.power_tenths = 0;
    if (code < 0) t.hedges[t.num_hedges++] = Hedge::Not;
    const auto near = [&](double v) { return std::fabs(frac - v) < 1e-6; };
    const int dd = static_cast<int>(std::round(100 * frac));
    if (near(0.0) || near(1.0) || dd == 0) {
      if (near(1.0)) ++term;
    } else if (dd == 99 && term == -1 && !output) {
      t.hedges[t.num_hedges++] = Hedge::Any;
      t.term = Token::kAnyTerm;
      return true;
    } else if (!output && dd == 5) {
      t.hedges[t.num_hedges++] = Hedge::Somewhat;
    } else if (!output && dd == 20) {
      t.hedges[t.num_hedges++] = Hedge::Very;
    } else if (!output && dd == 40) {
      t.hedges[t.num_hedges++] = Hedge::Very;
      t.hedges[t.num_hedges++] = Hedge::Very;
    } else {
      t.power_tenths = static_cast<std::uint8_t>(dd);
    }
    if (term < 0 || term >= static_cast<int>(num_terms))
      return fail("rule names term " + std::to_string(term + 1) + " of " +
                  (output ? "output " : "input ") + std::to_string(index + 1) + ", which has " +
                  std::to_string(num_terms));
    t.term = static_cast<std::uint8_t>(term);
    return true;
  }

  bool build_variable(const VariableText& v, bool input, std::size_t index) {
    const std::string what = (input ? "[Input" : "[Output") + std::to_string(index) + "]";
    if (v.name.empty()) return fail_at(v.line, what + " has no Name");
    if (v.name.size() > fuzzy::kMaxNameLength)
      return fail_at(v.name_line, "variable name '" + v.name + "' longer than 31 bytes");
    if (!v.has_range) return fail_at(v.line, what + " has no Range");
    if (!v.has_num_mfs) return fail_at(v.line, what + " has no NumMFs");
    // The MF lines are the terms, in line order, whatever their k and NumMFs say: MATLAB's
    // readfis and fuzzylite read them so, and files in the wild repeat a k (`MF2` twice) or
    // state a stale NumMFs.
    if (v.mfs.size() > Cap::terms)
      return fail_at(v.num_mfs_line,
                     "more membership functions than the capacity (" + capacity_text() + ")");
    // fuzzylite applies DefuzzMethod to every output whatever the Type: constant/linear terms
    // under a weighted one are Sugeno's, membership terms under it Tsukamoto's; a constant c
    // under an integral defuzzifier (a 'hybrid' export) is fuzzylite's Constant::membership, the
    // function c everywhere: Rectangle(-inf, inf) of height c.
    const bool weighted = fuzzy::is_sugeno(defuzzifier_);
    const bool constants_allowed = type_ == "sugeno" || type_ == "hybrid";
    for (std::size_t t = 0; t < v.mfs.size(); ++t) {
      const auto& mf = v.mfs[t];
      if (mf.name.size() > fuzzy::kMaxNameLength)
        return fail_at(mf.line, "term name '" + mf.name + "' longer than 31 bytes");
      std::string why;
      if (input) {
        auto& in = model_.inputs[index - 1];
        why = terms::make_membership(terms::Format::Fis, mf.type, mf.params, model_, in.terms[t]);
        (void)fuzzy::set_name(in.term_names[t], mf.name.data(), mf.name.size());
      } else {
        auto& out = model_.outputs[index - 1];
        auto& term = out.terms[t];
        (void)fuzzy::set_name(out.term_names[t], mf.name.data(), mf.name.size());
        if (mf.type == "constant" || mf.type == "linear") {
          if (!constants_allowed) why = "'" + mf.type + "' terms need Type='sugeno' or 'hybrid'";
          for (double x : mf.params)
            if (why.empty() && !std::isfinite(x)) why = "coefficients must be finite";
          std::vector<double> p = mf.params;
          const std::size_t want = mf.type == "constant" ? 1 : num_inputs_ + 1;
          while (p.size() > want && p.back() == 0.0)  // MATLAB 1.x zero padding
            p.pop_back();
          if (why.empty() && p.size() != want)
            why = "'" + mf.type + "' takes " + std::to_string(want) + " parameters, got " +
                  std::to_string(mf.params.size());
          if (why.empty() && !weighted) {
            if (mf.type == "linear")
              why = "'linear' terms under DefuzzMethod='" +
                    std::string(fuzzy::names(defuzzifier_).fis) + "' are not supported";
            else if (!(p[0] >= 0))
              why = "a negative 'constant' under an integral DefuzzMethod is not supported";
            else {
              term.membership.shape = fuzzy::Shape::Rectangle;
              term.membership.p = {-std::numeric_limits<double>::infinity(),
                                   std::numeric_limits<double>::infinity(), 0, 0};
              term.membership.height = p[0];
            }
          } else if (why.empty()) {
            term.kind = mf.type == "constant" ? fuzzy::OutputTermKind::Constant
                                              : fuzzy::OutputTermKind::Linear;
            for (std::size_t c = 0; c < p.size(); ++c)
              term.coefficients[c] = p[c];
          }
        } else {
          term.kind = fuzzy::OutputTermKind::Membership;
          why = terms::make_membership(terms::Format::Fis, mf.type, mf.params, model_,
                                       term.membership);
          // Under Type='sugeno' only a monotonic term means something (Tsukamoto's, as fuzzylite
          // reads it); any other is a Sugeno output written with a Mamdani term.
          if (why.empty() && type_ == "sugeno" && weighted && !fuzzy::is_monotonic(term.membership))
            why = "Type='sugeno' outputs take 'constant' or 'linear' terms, not '" + mf.type +
                  "' (of membership terms, a weighted DefuzzMethod takes only Tsukamoto's "
                  "monotonic ones: rampmf, sigmf, smf, zmf, concavemf)";
          if (why.empty() && options_.exact_centroid && defuzzifier_ == Defuzzifier::Centroid &&
              !fuzzy::is_piecewise_linear(term.membership))
            why = "'" + mf.type + "' is not piecewise linear (exact centroid requested)";
        }
      }
      if (!why.empty())
        return fail_at(mf.line, "MF" + std::to_string(mf.k) + " '" + mf.name + "': " + why);
    }
    if (input) {
      auto& in = model_.inputs[index - 1];
      (void)fuzzy::set_name(in.name, v.name.data(), v.name.size());
      in.min = v.min;
      in.max = v.max;
      in.enabled = v.enabled;
      in.num_terms = v.mfs.size();
      lines_.inputs.push_back(v.line);
    } else {
      auto& out = model_.outputs[index - 1];
      (void)fuzzy::set_name(out.name, v.name.data(), v.name.size());
      out.min = v.min;
      out.max = v.max;
      out.num_terms = v.mfs.size();
      out.defuzzifier = defuzzifier_;
      out.aggregation = aggregation_;
      out.has_aggregation = has_aggregation_;
      out.lock_range = v.lock_range;
      out.lock_previous = v.lock_previous;
      out.enabled = v.enabled;
      out.default_value = v.default_value;
      out.resolution = options_.fis_resolution;
      out.exact_centroid = options_.exact_centroid && !weighted;
      // Octave combines a Sugeno output's singletons at equal values with AggMethod (sum: the
      // plain weighted average, as fuzzylite; max, probor, ...: the singleton's degree is their
      // aggregation). fuzzylite ignores AggMethod under a weighted DefuzzMethod.
      out.merge_equal_singletons = weighted && has_aggregation_ &&
                                   aggregation_ != SNorm::UnboundedSum && out.num_terms > 0 &&
                                   out.terms[0].kind != fuzzy::OutputTermKind::Membership;
      if (!weighted && !has_aggregation_)
        return fail_at(agg_line_, "AggMethod='' but output '" + v.name +
                                      "' has an integral DefuzzMethod, which needs one");
      lines_.outputs.push_back(v.line);
    }
    return true;
  }

  bool finish() {
    if (!seen_system_) return fail_at(0, "missing [System] section");
    if (type_.empty()) return fail_at(0, "[System] has no Type");
    if (!has_inputs_ || !has_outputs_ || !has_rules_)
      return fail_at(0, "[System] needs NumInputs, NumOutputs and NumRules");
    if (!has_defuzz_) return fail_at(0, "[System] has no DefuzzMethod");
    const bool weighted = fuzzy::is_sugeno(defuzzifier_);
    if (type_ == "mamdani" ? weighted : (type_ == "sugeno" || type_ == "tsukamoto") && !weighted)
      return fail_at(defuzz_line_, "DefuzzMethod does not fit Type='" + type_ + "'");
    if (num_inputs_ < 1 || num_inputs_ > Cap::inputs)
      return fail_at(num_inputs_line_, "NumInputs must be in 1.." + std::to_string(Cap::inputs));
    if (num_outputs_ < 1 || num_outputs_ > Cap::outputs)
      return fail_at(num_outputs_line_, "NumOutputs must be in 1.." + std::to_string(Cap::outputs));
    if (num_rules_ > Cap::rules)
      return fail_at(num_rules_line_, "NumRules above the capacity (" + capacity_text() + ")");
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
    // More rule lines than NumRules: a stale count, read as fuzzylite reads it (every line; its
    // own AllTerms.fis example states 16 and holds 20). Fewer: a truncated file, refused.
    if (rules_.size() < num_rules_)
      return fail_at(num_rules_line_, "NumRules=" + std::to_string(num_rules_) + " but " +
                                          std::to_string(rules_.size()) + " rules follow");
    if (rules_.size() > Cap::rules)
      return fail_at(num_rules_line_, "more rules than the capacity (" + capacity_text() + ")");
    model_.num_blocks = 1;
    model_.blocks[0] = block_;
    for (const RuleText& rt : rules_) {
      line_ = rt.line;
      if (rt.antecedent.size() != num_inputs_)
        return fail("rule has " + std::to_string(rt.antecedent.size()) +
                    " antecedent indices, NumInputs is " + std::to_string(num_inputs_));
      if (rt.consequent.size() != num_outputs_)
        return fail("rule has " + std::to_string(rt.consequent.size()) +
                    " consequent indices, NumOutputs is " + std::to_string(num_outputs_));
      std::vector<Token> tokens;
      for (std::size_t i = 0; i < num_inputs_; ++i) {
        if (rt.antecedent[i] == 0) continue;
        Token t{Token::Kind::Proposition, static_cast<std::uint8_t>(i), 0, 0, {}, 0};
        int term = 0;
        if (!decode(rt.antecedent[i], i, model_.inputs[i].num_terms, term, t, false)) return false;
        tokens.push_back(t);
        if (tokens.size() > 1)
          tokens.push_back({rt.disjunction ? Token::Kind::Or : Token::Kind::And, 0, 0, 0, {}});
      }
      std::vector<Conclusion> conclusions;
      for (std::size_t o = 0; o < num_outputs_; ++o) {
        if (rt.consequent[o] == 0) continue;
        if (rt.consequent[o] < 0)
          return fail("negated consequent " + text::format_number(rt.consequent[o]) +
                      " is not supported");
        Token t{};
        int term = 0;
        if (!decode(rt.consequent[o], o, model_.outputs[o].num_terms, term, t, true)) return false;
        if (t.power_tenths != 0 && !fuzzy::is_sugeno(model_.outputs[o].defuzzifier))
          return fail("a hedge on a Mamdani conclusion (" + text::format_number(rt.consequent[o]) +
                      ": Octave raises the output's set to the power) is not supported");
        Conclusion c{static_cast<std::uint8_t>(o), t.term, t.num_hedges, t.hedges, t.power_tenths};
        conclusions.push_back(c);
      }
      if (conclusions.empty()) return fail("rule has no consequent (all indices 0)");
      // No input index (fuzzylite's .fis export of a rule testing an output, which .fis cannot
      // write): fuzzylite fails to load such a rule and never fires it; neither do we.
      if (tokens.empty()) continue;
      if (!model_.add_rule(tokens.data(), tokens.size(), conclusions.data(), conclusions.size(),
                           rt.weight, 0))
        return fail("rules exceed the capacity (" + capacity_text() + ")");
      lines_.rules.push_back(rt.line);
    }
    return check_model(model_, lines_, error_);
  }

  struct RuleText {
    int line = 0;
    std::vector<double> antecedent;
    std::vector<double> consequent;
    double weight = 1;
    bool disjunction = false;
  };

  Builder& model_;
  LoadError& error_;
  const LoadOptions& options_;
  int line_ = 0;
  bool seen_system_ = false;
  bool seen_rules_ = false;
  std::string type_;
  std::size_t num_inputs_ = 0, num_outputs_ = 0, num_rules_ = 0;
  int num_inputs_line_ = 0, num_outputs_line_ = 0, num_rules_line_ = 0;
  bool has_inputs_ = false, has_outputs_ = false, has_rules_ = false, has_defuzz_ = false;
  Defuzzifier defuzzifier_ = Defuzzifier::Centroid;
  int defuzz_line_ = 0;
  fuzzy::RuleBlock block_{};
  SNorm aggregation_ = SNorm::Maximum;
  bool has_aggregation_ = true;
  int agg_line_ = 0;
  std::map<std::size_t, VariableText> inputs_;
  std::map<std::size_t, VariableText> outputs_;
  std::vector<RuleText> rules_;
  SourceLines lines_;
};

}  // namespace

bool parse_fis(std::string_view text, const std::string& source, Model& model, LoadError& error,
               const LoadOptions& options) {
  const auto builder = std::make_unique<Builder>();
  return FisParser(source, *builder, error, options).parse(text::without_bom(text)) &&
         size_to_file(*builder, model, error);
}

}  // namespace fuzzypid::rulefile
