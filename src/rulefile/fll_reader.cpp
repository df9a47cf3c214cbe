// fuzzylite .fll reader (fll_writer.cpp writes the format). The grammar is fuzzylite 6's
// FllImporter: one `key: value` per line, `#` starts a comment, sections Engine / InputVariable /
// OutputVariable / RuleBlock (several rule blocks allowed). Names are read the way fuzzylite
// reads them (characters other than letters, digits, '_' and '.' dropped).
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "check.hpp"
#include "formula.hpp"
#include "fuzzypid/rulefile/rule_file.hpp"
#include "rules.hpp"
#include "terms.hpp"
#include "text.hpp"

namespace fuzzypid::rulefile {

namespace {

using fuzzy::Defuzzifier;
using fuzzy::TNorm;
using Cap = Builder::Capacity;

enum class Section { None, Engine, Input, Output, RuleBlock };

class FllParser {
 public:
  FllParser(const std::string& source, Builder& model, LoadError& error, const LoadOptions& options)
      : model_(model), error_(error), options_(options) {
    error_ = LoadError{source, 0, {}, {}};
  }

  bool parse(std::string_view text) {
    model_ = Builder{};
    model_.num_blocks = 0;
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
    end_block();
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
  void warn(const std::string& message) {
    error_.warnings.push_back(LoadError{error_.file, line_, message, {}}.to_string());
  }

  // Drops the rules of a disabled block (fuzzylite skips it).
  void end_block() {
    if (section_ == Section::RuleBlock && !block_enabled_) {
      model_.num_rules = block_first_rule_;
      model_.num_tokens = block_first_token_;
      model_.num_conclusions = block_first_conclusion_;
      lines_.rules.resize(block_first_rule_);
      --model_.num_blocks;
    }
  }

  bool property(std::string_view key, std::string_view value) {
    if (key == "Engine") {
      if (seen_engine_ || section_ != Section::None) return fail("'Engine:' must come first, once");
      seen_engine_ = true;
      section_ = Section::Engine;
      // Control characters are no part of a name any writer produces, and no format could write
      // them back (the .fis reader refuses them too).
      for (const char c : value)
        if (static_cast<unsigned char>(c) < 0x20 || c == '\x7f')
          return fail("engine name holds a control character (byte " +
                      std::to_string(static_cast<unsigned char>(c)) + ")");
      if (!fuzzy::set_name(model_.name, value.data(), value.size()))
        return fail("engine name longer than 31 bytes");
      return true;
    }
    if (key == "InputVariable" || key == "OutputVariable" || key == "RuleBlock") {
      end_block();
      if (!seen_engine_) seen_engine_ = true;  // fuzzylite allows an unnamed engine
    }
    if (key == "InputVariable" || key == "OutputVariable") {
      const bool input = key == "InputVariable";
      const std::string name = text::sanitized(value);
      if (!check_new_variable_name(name)) return false;
      const double inf = std::numeric_limits<double>::infinity();
      if (input) {
        if (model_.num_inputs == Cap::inputs)
          return fail("more inputs than the capacity (" + capacity_text() + ")");
        auto& in = model_.inputs[model_.num_inputs++];
        (void)fuzzy::set_name(in.name, name.data(), name.size());
        in.min = -inf;
        in.max = inf;
        lines_.inputs.push_back(line_);
        section_ = Section::Input;
      } else {
        if (model_.num_outputs == Cap::outputs)
          return fail("more outputs than the capacity (" + capacity_text() + ")");
        auto& out = model_.outputs[model_.num_outputs++];
        (void)fuzzy::set_name(out.name, name.data(), name.size());
        out.min = -inf;
        out.max = inf;
        out.exact_centroid = options_.exact_centroid;
        out.has_aggregation = false;  // fuzzylite's default: none
        lines_.outputs.push_back(line_);
        defuzzifier_seen_.push_back(false);
        aggregation_seen_.push_back(false);
        takagi_sugeno_type_.push_back(false);
        section_ = Section::Output;
      }
      return true;
    }
    if (key == "RuleBlock") {
      if (model_.num_blocks == Cap::blocks)
        return fail("more rule blocks than the capacity (" + std::to_string(Cap::blocks) + ")");
      auto& b = model_.blocks[model_.num_blocks++];
      b = fuzzy::RuleBlock{};
      b.has_conjunction = b.has_disjunction = b.has_implication = false;
      (void)fuzzy::set_name(b.name, value.data(), std::min(value.size(), fuzzy::kMaxNameLength));
      block_enabled_ = true;
      block_first_rule_ = model_.num_rules;
      block_first_token_ = model_.num_tokens;
      block_first_conclusion_ = model_.num_conclusions;
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

  bool check_new_variable_name(const std::string& name) {
    if (name.empty() || text::is_reserved(name))
      return fail("variable name '" + name + "' is empty or a rule keyword");
    if (name.size() > fuzzy::kMaxNameLength) return fail("variable name longer than 31 bytes");
    for (std::size_t i = 0; i < model_.num_inputs; ++i)
      if (text::name_of(model_.inputs[i].name) == name)
        return fail("duplicate variable name '" + name + "'");
    for (std::size_t o = 0; o < model_.num_outputs; ++o)
      if (text::name_of(model_.outputs[o].name) == name)
        return fail("duplicate variable name '" + name + "'");
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
    auto& in = model_.inputs[input ? model_.num_inputs - 1 : 0];
    auto& out = model_.outputs[input ? 0 : model_.num_outputs - 1];
    if (key == "enabled") {
      return boolean(value, input ? in.enabled : out.enabled);
    }
    if (key == "range") {
      const auto words = text::split_words(value);
      double lo = 0, hi = 0;
      if (words.size() != 2 || !text::parse_number(words[0], lo) ||
          !text::parse_number(words[1], hi))
        return fail("range takes two numbers, got '" + std::string(value) + "'");
      // min == max is allowed where the range is unused (Sugeno outputs; EngineModel::validate).
      if (!(input ? lo < hi : lo <= hi))
        return fail("range must have min < max, got '" + std::string(value) + "'");
      (input ? in.min : out.min) = lo;
      (input ? in.max : out.max) = hi;
      return true;
    }
    if (key == "lock-range") return boolean(value, input ? in.lock_range : out.lock_range);
    if (key == "term") return term(value);
    if (input) return fail("unknown InputVariable property '" + std::string(key) + "'");
    if (key == "aggregation" || key == "accumulation") {
      aggregation_seen_.back() = value != "none";
      out.has_aggregation = value != "none";
      if (value != "none" && !fuzzy::parse(value, fuzzy::Naming::Fuzzylite, out.aggregation))
        return fail("unsupported " + std::string(key) + " '" + std::string(value) + "'");
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
    if (key == "lock-previous" || key == "lock-valid") return boolean(value, out.lock_previous);
    return fail("unknown OutputVariable property '" + std::string(key) + "'");
  }

  bool defuzzifier(std::string_view value, fuzzy::OutputSpec<double, Cap>& out) {
    const auto words = text::split_words(value);
    if (words.empty()) return fail("defuzzifier needs a name");
    if (words[0] == "none") return true;
    Defuzzifier d{};
    if (!fuzzy::parse(words[0], fuzzy::Naming::Fuzzylite, d))
      return fail("unsupported defuzzifier '" + std::string(words[0]) + "'");
    out.defuzzifier = d;
    if (words.size() > 2) return fail("defuzzifier takes at most one parameter");
    if (!fuzzy::is_sugeno(d)) {
      out.resolution = 1000;  // fuzzylite 8's default (fuzzylite 6 writes it always)
      if (words.size() == 2) {
        std::size_t r = 0;
        if (!text::parse_count(words[1], r) || r < 1 || r > 100000000)
          return fail("resolution must be an integer in 1..1e8, got '" + std::string(words[1]) +
                      "'");
        out.resolution = static_cast<int>(r);
      }
    } else if (words.size() == 2 && words[1] != "Automatic" && words[1] != "TakagiSugeno" &&
               words[1] != "Tsukamoto") {
      return fail("unsupported weighted defuzzifier type '" + std::string(words[1]) +
                  "' (Automatic, TakagiSugeno or Tsukamoto)");
    } else {
      // fuzzylite's TakagiSugeno type evaluates a membership term at the degree (not Tsukamoto's
      // inverse); the engine does only the latter, so that combination is refused in finish().
      takagi_sugeno_type_.back() = words.size() == 2 && words[1] == "TakagiSugeno";
    }
    defuzzifier_seen_.back() = true;
    return true;
  }

  bool term(std::string_view value) {
    const bool input = section_ == Section::Input;
    const auto words = text::split_words(value);
    if (words.size() < 2) return fail("term needs a name, a type and parameters");
    const std::string name = text::sanitized(words[0]);
    const std::string_view type = words[1];
    if (name.empty() || text::is_reserved(name))
      return fail("term name '" + std::string(words[0]) + "' is empty or a rule keyword");
    if (name.size() > fuzzy::kMaxNameLength) return fail("term name longer than 31 bytes");
    std::vector<double> p;
    for (std::size_t k = 2; k < words.size() && type != "Function"; ++k) {
      double x = 0;
      if (!text::parse_number(words[k], x, true))
        return fail("term '" + name + "': '" + std::string(words[k]) + "' is not a number");
      p.push_back(x);
    }
    std::size_t& count = input ? model_.inputs[model_.num_inputs - 1].num_terms
                               : model_.outputs[model_.num_outputs - 1].num_terms;
    auto& names = input ? model_.inputs[model_.num_inputs - 1].term_names
                        : model_.outputs[model_.num_outputs - 1].term_names;
    // Two terms may share a name (fuzzylite's exports of MATLAB files do): a rule naming it means
    // the last, as fuzzylite 8 resolves it (fuzzylite 6 took the first; docs/rule_files.md).
    for (std::size_t t = 0; t < count; ++t)
      if (text::name_of(names[t]) == name) {
        warn("term '" + name + "' repeats the name of an earlier term of the variable; rules " +
             "naming it mean the last, as fuzzylite 8 reads them");
        break;
      }
    if (count == Cap::terms)
      return fail("more terms in a variable than the capacity (" + capacity_text() + ")");
    if (type == "Function") {
      // Compiled in finish(), when every variable a formula may name is known.
      const std::string_view rest =
          value.substr(static_cast<std::size_t>(words[1].data() + words[1].size() - value.data()));
      formulas_.push_back({input, input ? model_.num_inputs - 1 : model_.num_outputs - 1, count,
                           name, std::string(text::trim(rest)), line_});
    } else if (input) {
      if (type == "Constant" || type == "Linear")
        return fail("term '" + name + "': '" + std::string(type) +
                    "' is an output term (not a membership function of an input)");
      auto& t = model_.inputs[model_.num_inputs - 1].terms[count];
      const std::string why = terms::make_membership(terms::Format::Fll, type, p, model_, t);
      if (!why.empty()) return fail("term '" + name + "': " + why);
    } else {
      auto& t = model_.outputs[model_.num_outputs - 1].terms[count];
      if (type == "Constant" || type == "Linear") {
        for (double x : p)
          if (!std::isfinite(x)) return fail("term '" + name + "': coefficients must be finite");
        if (type == "Constant") {
          if (p.size() != 1) return fail("term '" + name + "': Constant takes 1 value");
          t.kind = fuzzy::OutputTermKind::Constant;
          t.coefficients[0] = p[0];
        } else {
          const std::size_t n = model_.num_inputs;
          if (p.size() != n && p.size() != n + 1)
            return fail("term '" + name + "': Linear takes " + std::to_string(n) + " or " +
                        std::to_string(n + 1) + " coefficients, got " + std::to_string(p.size()));
          t.kind = fuzzy::OutputTermKind::Linear;
          for (std::size_t k = 0; k < p.size(); ++k)
            t.coefficients[k] = p[k];
        }
      } else {
        t.kind = fuzzy::OutputTermKind::Membership;
        const std::string why =
            terms::make_membership(terms::Format::Fll, type, p, model_, t.membership);
        if (!why.empty()) return fail("term '" + name + "': " + why);
      }
    }
    (void)fuzzy::set_name(names[count], name.data(), name.size());
    ++count;
    return true;
  }

  bool rule_block_property(std::string_view key, std::string_view value) {
    auto& b = model_.blocks[model_.num_blocks - 1];
    if (key == "enabled") return boolean(value, block_enabled_);
    if (key == "conjunction" || key == "implication" ||
        (key == "activation" && fuzzy::parse(value, fuzzy::Naming::Fuzzylite, b.implication))) {
      // fuzzylite 5 wrote the implication as `activation: <t-norm>`.
      const bool conj = key == "conjunction";
      TNorm& op = conj ? b.conjunction : b.implication;
      bool& has = conj ? b.has_conjunction : b.has_implication;
      if (value == "none") {
        has = false;
        return true;
      }
      if (!fuzzy::parse(value, fuzzy::Naming::Fuzzylite, op))
        return fail("unsupported " + std::string(key) + " '" + std::string(value) + "'");
      has = true;
      return true;
    }
    if (key == "disjunction") {
      if (value == "none") {
        b.has_disjunction = false;
        return true;
      }
      if (!fuzzy::parse(value, fuzzy::Naming::Fuzzylite, b.disjunction))
        return fail("unsupported disjunction '" + std::string(value) + "'");
      b.has_disjunction = true;
      return true;
    }
    if (key == "activation") return activation(value, b);
    if (key == "rule") {
      const std::string why = rules::parse_rule(value, model_, model_.num_blocks - 1, false,
                                                rules::DuplicateTerm::Last);
      if (!why.empty()) return fail(why);
      lines_.rules.push_back(line_);
      return true;
    }
    return fail("unknown RuleBlock property '" + std::string(key) + "'");
  }

  // General | Proportional | Threshold [cmp [value]] | First|Last [n [threshold]] | Highest|Lowest
  // [n]
  bool activation(std::string_view value, fuzzy::RuleBlock& b) {
    const auto words = text::split_words(value);
    if (words.empty() || words[0] == "none" || words[0] == "General") {
      b.activation = fuzzy::ActivationMethod::General;
      return words.size() <= 1 || fail("General takes no parameters");
    }
    const auto method = fuzzypid::parse_enum(fuzzy::kActivationNames, words[0]);
    if (!method) return fail("unsupported activation '" + std::string(words[0]) + "'");
    b.activation = *method;
    using fuzzy::ActivationMethod;
    const auto count = [&](std::size_t at) {
      std::size_t n = 0;
      if (words.size() > at && (!text::parse_count(words[at], n) || n < 1 || n > 1000000))
        return fail("activation '" + std::string(words[0]) +
                    "' takes a number of rules >= 1, got '" + std::string(words[at]) + "'");
      b.count = words.size() > at ? static_cast<std::uint32_t>(n) : 1;
      return true;
    };
    const auto threshold = [&](std::size_t at) {
      double t = 0;
      if (words.size() > at && (!text::parse_number(words[at], t) || !(t >= 0 && t <= 1)))
        return fail("activation threshold must be a number in [0, 1], got '" +
                    std::string(words[at]) + "'");
      b.threshold = words.size() > at ? t : 0.0;
      return true;
    };
    switch (b.activation) {
      case ActivationMethod::Proportional:
        return words.size() == 1 || fail("Proportional takes no parameters");
      case ActivationMethod::Threshold: {
        b.comparison = fuzzy::Comparison::GreaterThanOrEqualTo;
        if (words.size() > 3) return fail("Threshold takes a comparison and a value");
        if (words.size() > 1) {
          const auto c = fuzzypid::parse_enum(fuzzy::kComparisonNames, words[1]);
          if (!c)
            return fail("Threshold comparison must be <, <=, ==, !=, >= or >, got '" +
                        std::string(words[1]) + "'");
          b.comparison = *c;
        }
        return threshold(2);
      }
      case ActivationMethod::First:
      case ActivationMethod::Last:
        if (words.size() > 3) return fail("First/Last take a number of rules and a threshold");
        return count(1) && threshold(2);
      default:
        if (words.size() > 2) return fail("Highest/Lowest take a number of rules");
        return count(1);
    }
  }

  bool finish() {
    if (!seen_engine_) return fail_at(0, "missing 'Engine:' line");
    if (model_.num_inputs == 0) return fail_at(0, "no InputVariable");
    if (model_.num_outputs == 0) return fail_at(0, "no OutputVariable");
    if (model_.num_blocks == 0) {  // no rule block: every output takes its default
      model_.num_blocks = 1;
      model_.blocks[0] = fuzzy::RuleBlock{};
    }
    if (!formula::compile_all(formulas_, model_, error_)) return false;
    for (std::size_t o = 0; o < model_.num_outputs; ++o) {
      auto& out = model_.outputs[o];
      const int at = lines_.outputs[o];
      if (!defuzzifier_seen_[o]) return fail_at(at, "output has no defuzzifier");
      out.group_by_term = fuzzy::fuzzylite8_groups_by_term(out);
      if (!fuzzy::is_sugeno(out.defuzzifier) && !aggregation_seen_[o])
        return fail_at(at, "output needs an aggregation");
      if (takagi_sugeno_type_[o] && out.num_terms > 0 &&
          out.terms[0].kind == fuzzy::OutputTermKind::Membership)
        return fail_at(at,
                       "a TakagiSugeno weighted defuzzifier over membership terms is not "
                       "supported (Tsukamoto or Automatic is)");
    }
    return check_model(model_, lines_, error_);
  }

  Builder& model_;
  LoadError& error_;
  const LoadOptions& options_;
  Section section_ = Section::None;
  int line_ = 0;
  std::vector<formula::Pending> formulas_;  // Function terms, compiled in finish()
  bool seen_engine_ = false;
  bool block_enabled_ = true;
  std::size_t block_first_rule_ = 0, block_first_token_ = 0, block_first_conclusion_ = 0;
  std::vector<bool> defuzzifier_seen_;
  std::vector<bool> aggregation_seen_;
  std::vector<bool> takagi_sugeno_type_;
  SourceLines lines_;
};

}  // namespace

bool parse_fll(std::string_view text, const std::string& source, Model& model, LoadError& error,
               const LoadOptions& options) {
  const auto builder = std::make_unique<Builder>();
  return FllParser(source, *builder, error, options).parse(text::without_bom(text)) &&
         size_to_file(*builder, model, error);
}

}  // namespace fuzzypid::rulefile
