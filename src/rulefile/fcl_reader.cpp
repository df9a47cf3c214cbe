// IEC 61131-7 Fuzzy Control Language (.fcl) reader, the subset fuzzylite 6's FclImporter reads
// (fcl_writer.cpp writes it):
//
//   FUNCTION_BLOCK name
//   VAR_INPUT  name : REAL; ... END_VAR          VAR_OUTPUT name : REAL; ... END_VAR
//   FUZZIFY name   RANGE := (min .. max); TERM t := <term>; [LOCK : RANGE;]   END_FUZZIFY
//   DEFUZZIFY name RANGE := (min .. max); TERM t := <term>; METHOD : COG|COA|MM|LM|RM|COGS|COGSS;
//                  ACCU : <s-norm>; DEFAULT := <number>|nan; [LOCK : RANGE;]  END_DEFUZZIFY
//   RULEBLOCK name AND : <t-norm>; OR : <s-norm>; ACT : <t-norm>; [ACCU : <s-norm>;]
//                  RULE n : if ... then ... [with w];                        END_RULEBLOCK
//   END_FUNCTION_BLOCK
//
// <term> is a number (a singleton consequent, fuzzylite's Constant), points "(x, y) (x, y) ..."
// (fuzzylite's Discrete), or a fuzzylite term class with its parameters ("Triangle 0 5 10").
// Comments: //, (* *) and /* */. Keywords in any case; names are case-sensitive and sanitised
// the way fuzzylite does. Statements end with ';' (optional at the end of a line). ACCU in a
// RULEBLOCK (the standard's place) sets the aggregation of every output that has none of its own.
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

using fuzzy::SNorm;
using fuzzy::TNorm;
using Cap = Builder::Capacity;

struct Statement {
  int line = 0;
  std::string text;
};

// Removes comments (keeping line breaks) and splits into statements at ';' and line ends.
bool statements(std::string_view in, std::vector<Statement>& out, int& bad_line) {
  std::string cur;
  int line = 1;
  int start_line = 1;
  const auto flush = [&] {
    const std::string_view t = text::trim(cur);
    if (!t.empty()) out.push_back({start_line, std::string(t)});
    cur.clear();
  };
  for (std::size_t k = 0; k < in.size(); ++k) {
    const char c = in[k];
    const char n = k + 1 < in.size() ? in[k + 1] : '\0';
    if (c == '/' && n == '/') {
      while (k < in.size() && in[k] != '\n')
        ++k;
      --k;
      continue;
    }
    if ((c == '(' && n == '*') || (c == '/' && n == '*')) {
      const char* close = c == '(' ? "*)" : "*/";
      const std::size_t end = in.find(close, k + 2);
      if (end == std::string_view::npos) {
        bad_line = line;
        return false;
      }
      for (std::size_t j = k; j < end; ++j)
        if (in[j] == '\n') ++line;
      k = end + 1;
      cur += ' ';
      continue;
    }
    if (c == '\n' || c == ';') {
      flush();
      if (c == '\n') ++line;
      start_line = line;
      continue;
    }
    if (cur.empty() && (c == ' ' || c == '\t' || c == '\r')) {
      start_line = line;
      continue;
    }
    cur += c;
  }
  flush();
  return true;
}

class FclParser {
 public:
  FclParser(const std::string& source, Builder& model, LoadError& error, const LoadOptions& options)
      : model_(model), error_(error), options_(options) {
    error_ = LoadError{source, 0, {}, {}};
  }

  bool parse(std::string_view text) {
    model_ = Builder{};
    model_.num_blocks = 0;
    std::vector<Statement> list;
    int bad = 0;
    if (!statements(text, list, bad)) return fail_at(bad, "unterminated comment");
    for (const Statement& st : list) {
      line_ = st.line;
      if (!statement(st.text)) return false;
    }
    return finish();
  }

 private:
  enum class Block { None, Function, VarInput, VarOutput, Fuzzify, Defuzzify, RuleBlock, Done };

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

  static std::string first_word(const std::string& s) {
    std::size_t k = 0;
    while (k < s.size() && s[k] != ' ' && s[k] != '\t' && s[k] != ':')
      ++k;
    return s.substr(0, k);
  }
  static std::string rest_after(const std::string& s, std::size_t n) {
    return std::string(text::trim(std::string_view(s).substr(n)));
  }

  int find_input(const std::string& name) const {
    for (std::size_t i = 0; i < model_.num_inputs; ++i)
      if (text::name_of(model_.inputs[i].name) == name) return static_cast<int>(i);
    return -1;
  }
  int find_output(const std::string& name) const {
    for (std::size_t o = 0; o < model_.num_outputs; ++o)
      if (text::name_of(model_.outputs[o].name) == name) return static_cast<int>(o);
    return -1;
  }

  bool statement(const std::string& s) {
    const std::string word = first_word(s);
    const std::string kw = text::lower(word);
    const std::string rest = rest_after(s, word.size());
    if (kw == "function_block") {
      if (block_ != Block::None) return fail("FUNCTION_BLOCK must come first, once");
      block_ = Block::Function;
      const std::string name = text::sanitized(rest);
      if (!rest.empty())
        (void)fuzzy::set_name(model_.name, name.data(),
                              std::min(name.size(), fuzzy::kMaxNameLength));
      return true;
    }
    if (block_ == Block::None) return fail("expected FUNCTION_BLOCK, got '" + s + "'");
    if (block_ == Block::Done) return fail("text after END_FUNCTION_BLOCK: '" + s + "'");
    if (kw == "end_function_block") {
      if (block_ != Block::Function) return fail("END_FUNCTION_BLOCK inside another block");
      block_ = Block::Done;
      return true;
    }
    if (kw == "var_input" || kw == "var_output") {
      if (block_ != Block::Function) return fail(word + " inside another block");
      block_ = kw == "var_input" ? Block::VarInput : Block::VarOutput;
      return true;
    }
    if (kw == "end_var") {
      if (block_ != Block::VarInput && block_ != Block::VarOutput)
        return fail("END_VAR without VAR_INPUT or VAR_OUTPUT");
      block_ = Block::Function;
      return true;
    }
    if (block_ == Block::VarInput || block_ == Block::VarOutput) return declaration(s);
    if (kw == "fuzzify" || kw == "defuzzify") {
      if (block_ != Block::Function) return fail(word + " inside another block");
      const std::string name = text::sanitized(rest);
      const int i = kw == "fuzzify" ? find_input(name) : find_output(name);
      if (i < 0)
        return fail(word + " names '" + rest + "', which is not declared in " +
                    (kw == "fuzzify" ? "VAR_INPUT" : "VAR_OUTPUT"));
      current_ = static_cast<std::size_t>(i);
      block_ = kw == "fuzzify" ? Block::Fuzzify : Block::Defuzzify;
      (kw == "fuzzify" ? lines_.inputs : lines_.outputs)[current_] = line_;
      return true;
    }
    if (kw == "end_fuzzify" || kw == "end_defuzzify") {
      if (block_ != (kw == "end_fuzzify" ? Block::Fuzzify : Block::Defuzzify))
        return fail(word + " does not close the open block");
      block_ = Block::Function;
      return true;
    }
    if (kw == "ruleblock") {
      if (block_ != Block::Function) return fail("RULEBLOCK inside another block");
      if (model_.num_blocks == Cap::blocks)
        return fail("more rule blocks than the capacity (" + std::to_string(Cap::blocks) + ")");
      auto& b = model_.blocks[model_.num_blocks++];
      b = fuzzy::RuleBlock{};
      b.has_conjunction = b.has_disjunction = b.has_implication = false;
      const std::string name = text::sanitized(rest);
      (void)fuzzy::set_name(b.name, name.data(), std::min(name.size(), fuzzy::kMaxNameLength));
      block_ = Block::RuleBlock;
      return true;
    }
    if (kw == "end_ruleblock") {
      if (block_ != Block::RuleBlock) return fail("END_RULEBLOCK without RULEBLOCK");
      block_ = Block::Function;
      return true;
    }
    switch (block_) {
      case Block::Fuzzify:
      case Block::Defuzzify:
        return variable_statement(kw, s);
      case Block::RuleBlock:
        return rule_block_statement(kw, s);
      default:
        return fail("unexpected '" + s + "' outside FUZZIFY, DEFUZZIFY and RULEBLOCK");
    }
  }

  bool declaration(const std::string& s) {
    const std::size_t colon = s.find(':');
    if (colon == std::string::npos) return fail("expected 'name : REAL', got '" + s + "'");
    const std::string name = text::sanitized(text::trim(std::string_view(s).substr(0, colon)));
    const std::string type(text::trim(std::string_view(s).substr(colon + 1)));
    if (!text::iequals(type, "REAL")) return fail("variable type '" + type + "' (expected REAL)");
    if (name.empty() || text::is_reserved(name) || name.size() > fuzzy::kMaxNameLength)
      return fail("variable name '" + name + "' is empty, a rule keyword or longer than 31 bytes");
    if (find_input(name) >= 0 || find_output(name) >= 0)
      return fail("duplicate variable name '" + name + "'");
    const double inf = std::numeric_limits<double>::infinity();
    if (block_ == Block::VarInput) {
      if (model_.num_inputs == Cap::inputs)
        return fail("more inputs than the capacity (" + capacity_text() + ")");
      auto& in = model_.inputs[model_.num_inputs++];
      (void)fuzzy::set_name(in.name, name.data(), name.size());
      in.min = -inf;
      in.max = inf;
      lines_.inputs.push_back(line_);
    } else {
      if (model_.num_outputs == Cap::outputs)
        return fail("more outputs than the capacity (" + capacity_text() + ")");
      auto& out = model_.outputs[model_.num_outputs++];
      (void)fuzzy::set_name(out.name, name.data(), name.size());
      out.min = -inf;
      out.max = inf;
      out.resolution = options_.fis_resolution;
      out.exact_centroid = options_.exact_centroid;
      lines_.outputs.push_back(line_);
      method_seen_.push_back(false);
      accu_seen_.push_back(false);
    }
    return true;
  }

  // "KEY : VALUE" or "KEY := VALUE" -> VALUE
  bool value_of(const std::string& s, std::string& value, bool assign) {
    const std::size_t at = s.find(assign ? ":=" : ":");
    if (at == std::string::npos)
      return fail(std::string("expected '") + (assign ? ":=" : ":") + "' in '" + s + "'");
    value = std::string(text::trim(std::string_view(s).substr(at + (assign ? 2 : 1))));
    return true;
  }

  bool variable_statement(const std::string& kw, const std::string& s) {
    const bool input = block_ == Block::Fuzzify;
    auto& in = model_.inputs[input ? current_ : 0];
    auto& out = model_.outputs[input ? 0 : current_];
    std::string value;
    if (kw == "range") {
      if (!value_of(s, value, true)) return false;
      std::string v = value;
      if (v.size() < 2 || v.front() != '(' || v.back() != ')')
        return fail("RANGE must be (min .. max), got '" + value + "'");
      v = v.substr(1, v.size() - 2);
      const std::size_t dots = v.find("..");
      double lo = 0, hi = 0;
      if (dots == std::string::npos || !text::parse_number(text::trim(v.substr(0, dots)), lo) ||
          !text::parse_number(text::trim(v.substr(dots + 2)), hi) ||
          !(input ? lo < hi : lo <= hi))  // min == max where unused: EngineModel::validate
        return fail("RANGE must be (min .. max) with numbers min < max, got '" + value + "'");
      (input ? in.min : out.min) = lo;
      (input ? in.max : out.max) = hi;
      return true;
    }
    if (kw == "term") return term(s, input);
    if (kw == "lock") {
      if (!value_of(s, value, false)) return false;
      // RANGE, PREVIOUS (outputs: keep the last value when no rule fires) or both, '|'-separated.
      std::string flags = value;
      bool range = false, previous = false;
      for (std::size_t bar; !flags.empty();) {
        bar = flags.find('|');
        const std::string flag(text::trim(flags.substr(0, bar)));
        flags = bar == std::string::npos ? std::string() : flags.substr(bar + 1);
        if (text::iequals(flag, "RANGE")) {
          range = true;
        } else if (text::iequals(flag, "PREVIOUS") && !input) {
          previous = true;
        } else {
          return fail("LOCK : " + value +
                      " is not supported (RANGE, PREVIOUS or PREVIOUS | RANGE)");
        }
      }
      if (range) (input ? in.lock_range : out.lock_range) = true;
      if (previous) out.lock_previous = true;
      return true;
    }
    if (input) return fail("unknown FUZZIFY statement '" + s + "'");
    if (kw == "method") {
      if (!value_of(s, value, false)) return false;
      if (!fuzzy::parse(value, fuzzy::Naming::Fcl, out.defuzzifier))
        return fail("unsupported METHOD '" + value + "' (COG, COA, MM, LM, RM, COGS, COGSS)");
      method_seen_[current_] = true;
      return true;
    }
    if (kw == "accu") {
      if (!value_of(s, value, false)) return false;
      if (!snorm(value, out.aggregation)) return fail("unsupported ACCU '" + value + "'");
      accu_seen_[current_] = true;
      return true;
    }
    if (kw == "default") {
      if (!value_of(s, value, true)) return false;
      // `DEFAULT := NC` (IEC 61131-7: no change) keeps the previous value, NaN before any;
      // fuzzylite writes `DEFAULT := v | NC`: v until a rule has fired, then the previous value.
      const std::size_t bar = value.find('|');
      if (bar != std::string::npos) {
        if (!text::iequals(text::trim(value.substr(bar + 1)), "NC"))
          return fail("DEFAULT := v | NC expected, got '" + value + "'");
        out.lock_previous = true;
        value = std::string(text::trim(value.substr(0, bar)));
      }
      if (text::iequals(value, "NC")) {
        out.lock_previous = true;
        value = "nan";
      }
      double d = 0;
      if (!text::parse_number(value, d, true) || std::isinf(d))
        return fail("DEFAULT must be a finite number or nan, got '" + value + "'");
      out.default_value = d;
      return true;
    }
    return fail("unknown DEFUZZIFY statement '" + s + "'");
  }

  static bool snorm(const std::string& v, SNorm& out) {
    return fuzzy::parse(v, fuzzy::Naming::Fcl, out) ||
           fuzzy::parse(v, fuzzy::Naming::Fuzzylite, out) ||
           (v == "SUM" && (out = SNorm::UnboundedSum, true));
  }
  static bool tnorm(const std::string& v, TNorm& out) {
    return fuzzy::parse(v, fuzzy::Naming::Fcl, out) ||
           fuzzy::parse(v, fuzzy::Naming::Fuzzylite, out);
  }

  bool term(const std::string& s, bool input) {
    const std::size_t assign = s.find(":=");
    if (assign == std::string::npos) return fail("expected 'TERM name := ...', got '" + s + "'");
    const std::string name = text::sanitized(text::trim(std::string_view(s).substr(4, assign - 4)));
    std::string spec(text::trim(std::string_view(s).substr(assign + 2)));
    if (name.empty() || text::is_reserved(name) || name.size() > fuzzy::kMaxNameLength)
      return fail("term name '" + name + "' is empty, a rule keyword or longer than 31 bytes");
    std::size_t& count =
        input ? model_.inputs[current_].num_terms : model_.outputs[current_].num_terms;
    auto& names = input ? model_.inputs[current_].term_names : model_.outputs[current_].term_names;
    // Two terms may share a name (fuzzylite's exports of MATLAB files do): a rule naming it means
    // the first, as fuzzylite's Variable::getTerm resolves it.
    for (std::size_t t = 0; t < count; ++t)
      if (text::name_of(names[t]) == name) {
        warn("term '" + name + "' repeats the name of an earlier term of the variable; rules " +
             "naming it mean the first");
        break;
      }
    if (count == Cap::terms)
      return fail("more terms in a variable than the capacity (" + capacity_text() + ")");
    std::string type;
    std::vector<double> p;
    double single = 0;
    const auto spec_words = text::split_words(spec);
    if (!spec_words.empty() && spec_words[0] == "Function") {
      // Compiled in finish(), when every variable a formula may name is known.
      formulas_.push_back({input, current_, count, name,
                           std::string(text::trim(std::string_view(spec).substr(8))), line_});
    } else if (text::parse_number(spec, single)) {
      type = "Constant";
      p.push_back(single);
    } else {
      std::string spaced;
      for (char c : spec)
        spaced += (c == '(' || c == ')' || c == ',') ? ' ' : c;
      auto words = text::split_words(spaced);
      std::size_t first = 0;
      if (!spec.empty() && spec[0] == '(') {
        type = "Discrete";
      } else {
        if (words.empty()) return fail("TERM '" + name + "' has no definition");
        type = std::string(words[0]);
        first = 1;
      }
      for (std::size_t k = first; k < words.size(); ++k) {
        double x = 0;
        if (!text::parse_number(words[k], x, true))
          return fail("term '" + name + "': '" + std::string(words[k]) + "' is not a number");
        p.push_back(x);
      }
    }
    if (type.empty()) {
      // a Function term, compiled in finish()
    } else if (input) {
      if (type == "Constant" || type == "Linear")
        return fail("term '" + name + "': a " + (type == "Constant" ? "singleton" : "Linear") +
                    " term is not a membership function of an input");
      const std::string why = terms::make_membership(terms::Format::Fcl, type, p, model_,
                                                     model_.inputs[current_].terms[count]);
      if (!why.empty()) return fail("term '" + name + "': " + why);
    } else {
      auto& t = model_.outputs[current_].terms[count];
      if (type == "Constant" || type == "Linear") {
        for (double x : p)
          if (!std::isfinite(x)) return fail("term '" + name + "': coefficients must be finite");
        const std::size_t n = model_.num_inputs;
        if (type == "Constant" && p.size() != 1)
          return fail("term '" + name + "': Constant takes 1 value");
        if (type == "Linear" && p.size() != n && p.size() != n + 1)
          return fail("term '" + name + "': Linear takes " + std::to_string(n) + " or " +
                      std::to_string(n + 1) + " coefficients, got " + std::to_string(p.size()));
        t.kind =
            type == "Constant" ? fuzzy::OutputTermKind::Constant : fuzzy::OutputTermKind::Linear;
        for (std::size_t k = 0; k < p.size(); ++k)
          t.coefficients[k] = p[k];
      } else {
        t.kind = fuzzy::OutputTermKind::Membership;
        const std::string why =
            terms::make_membership(terms::Format::Fcl, type, p, model_, t.membership);
        if (!why.empty()) return fail("term '" + name + "': " + why);
      }
    }
    (void)fuzzy::set_name(names[count], name.data(), name.size());
    ++count;
    return true;
  }

  bool rule_block_statement(const std::string& kw, const std::string& s) {
    auto& b = model_.blocks[model_.num_blocks - 1];
    std::string value;
    if (kw == "and" || kw == "act") {
      if (!value_of(s, value, false)) return false;
      TNorm& op = kw == "and" ? b.conjunction : b.implication;
      bool& has = kw == "and" ? b.has_conjunction : b.has_implication;
      has = !text::iequals(value, "NONE");
      if (has && !tnorm(value, op))
        return fail("unsupported " + text::lower(kw) + " operator '" + value + "'");
      return true;
    }
    if (kw == "or") {
      if (!value_of(s, value, false)) return false;
      b.has_disjunction = !text::iequals(value, "NONE");
      if (b.has_disjunction && !snorm(value, b.disjunction))
        return fail("unsupported OR operator '" + value + "'");
      return true;
    }
    if (kw == "accu") {
      if (!value_of(s, value, false)) return false;
      if (!snorm(value, block_accu_)) return fail("unsupported ACCU '" + value + "'");
      has_block_accu_ = true;
      return true;
    }
    if (kw == "rule") {
      // RULE n : if ... [;]
      std::size_t colon = s.find(':');
      if (colon == std::string::npos) colon = 3;
      const std::string rule_text = rest_after(s, colon + 1);
      const std::string why = rules::parse_rule(rule_text, model_, model_.num_blocks - 1, true);
      if (!why.empty()) return fail(why);
      lines_.rules.push_back(line_);
      return true;
    }
    return fail("unknown RULEBLOCK statement '" + s + "'");
  }

  bool finish() {
    if (block_ == Block::None) return fail_at(0, "missing FUNCTION_BLOCK");
    if (block_ != Block::Done)
      return fail_at(0, "missing END_FUNCTION_BLOCK or an END_ of a block");
    if (model_.num_inputs == 0) return fail_at(0, "no VAR_INPUT variable");
    if (model_.num_outputs == 0) return fail_at(0, "no VAR_OUTPUT variable");
    if (model_.num_blocks == 0) {
      model_.num_blocks = 1;
      model_.blocks[0] = fuzzy::RuleBlock{};
    }
    for (std::size_t o = 0; o < model_.num_outputs; ++o) {
      auto& out = model_.outputs[o];
      if (!method_seen_[o]) return fail_at(lines_.outputs[o], "output has no METHOD");
      if (!accu_seen_[o] && has_block_accu_) {
        out.aggregation = block_accu_;
        accu_seen_[o] = true;
      }
      out.has_aggregation = accu_seen_[o];
      if (!fuzzy::is_sugeno(out.defuzzifier) && !accu_seen_[o])
        return fail_at(lines_.outputs[o], "output needs an ACCU (aggregation) method");
    }
    if (!formula::compile_all(formulas_, model_, error_)) return false;
    // fuzzylite 8 reads no .fcl; its .fll meaning is kept for the same system in either format.
    for (std::size_t o = 0; o < model_.num_outputs; ++o)
      model_.outputs[o].group_by_term = fuzzy::fuzzylite8_groups_by_term(model_.outputs[o]);
    return check_model(model_, lines_, error_);
  }

  Builder& model_;
  LoadError& error_;
  const LoadOptions& options_;
  Block block_ = Block::None;
  std::size_t current_ = 0;
  int line_ = 0;
  std::vector<formula::Pending> formulas_;  // Function terms, compiled in finish()
  std::vector<bool> method_seen_, accu_seen_;
  SNorm block_accu_ = SNorm::Maximum;
  bool has_block_accu_ = false;
  SourceLines lines_;
};

}  // namespace

bool parse_fcl(std::string_view text, const std::string& source, Model& model, LoadError& error,
               const LoadOptions& options) {
  const auto builder = std::make_unique<Builder>();
  return FclParser(source, *builder, error, options).parse(text::without_bom(text)) &&
         size_to_file(*builder, model, error);
}

}  // namespace fuzzypid::rulefile
