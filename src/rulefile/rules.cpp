#include "rules.hpp"

#include <vector>

#include "text.hpp"

namespace fuzzypid::rulefile::rules {

namespace {

using fuzzy::Conclusion;
using fuzzy::Hedge;
using fuzzy::Token;

std::vector<std::string> tokenize(std::string_view text) {
  std::vector<std::string> out;
  std::string cur;
  const auto flush = [&] {
    if (!cur.empty()) out.push_back(cur);
    cur.clear();
  };
  for (char c : text) {
    if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
      flush();
    } else if (c == '(' || c == ')') {
      flush();
      out.emplace_back(1, c);
    } else {
      cur += c;
    }
  }
  flush();
  return out;
}

class Parser {
 public:
  Parser(std::vector<std::string> words, Builder& model, bool any_case, DuplicateTerm duplicate)
      : w_(std::move(words)), model_(model), any_case_(any_case), duplicate_(duplicate) {}

  std::string parse(std::size_t block) {
    if (!is("if")) return "rule must start with 'if'";
    ++k_;
    std::string why = expression(0);
    if (!why.empty()) return why;
    if (k_ >= w_.size() || !is("then"))
      return k_ < w_.size() ? "expected 'and', 'or' or 'then', got '" + w_[k_] + "'"
                            : "rule has no 'then'";
    ++k_;
    for (;;) {
      why = conclusion();
      if (!why.empty()) return why;
      if (k_ == w_.size()) break;
      if (is("with")) {
        ++k_;
        if (k_ + 1 != w_.size()) return "'with' takes one weight at the end of the rule";
        if (!text::parse_number(w_[k_], weight_) || !(weight_ >= 0 && weight_ <= 1))
          return "rule weight must be a number in [0, 1], got '" + w_[k_] + "'";
        k_ = w_.size();
        break;
      }
      if (!is("and")) return "expected 'and' or 'with', got '" + w_[k_] + "'";
      ++k_;
    }
    if (tokens_.size() > Model::Capacity::rule_tokens)
      return "antecedent longer than " + std::to_string(Model::Capacity::rule_tokens) +
             " propositions and connectives";
    if (!model_.add_rule(tokens_.data(), tokens_.size(), conclusions_.data(), conclusions_.size(),
                         weight_, block))
      return "more rules or propositions than the capacity (" +
             std::to_string(Model::Capacity::rules) + " rules)";
    return {};
  }

 private:
  bool is(const char* keyword) const {
    if (k_ >= w_.size()) return false;
    return any_case_ ? text::iequals(w_[k_], keyword) : w_[k_] == keyword;
  }
  bool hedge(Hedge& h) const {
    if (k_ >= w_.size()) return false;
    return fuzzy::parse(any_case_ ? text::lower(w_[k_]) : w_[k_], h);
  }

  std::string expression(int depth) {
    if (depth > 32) return "parentheses nested too deeply";
    std::string why = conjunction(depth);
    while (why.empty() && is("or")) {
      ++k_;
      why = conjunction(depth);
      tokens_.push_back({Token::Kind::Or, 0, 0, 0, {}});
    }
    return why;
  }

  std::string conjunction(int depth) {
    std::string why = primary(depth);
    while (why.empty() && is("and")) {
      ++k_;
      why = primary(depth);
      tokens_.push_back({Token::Kind::And, 0, 0, 0, {}});
    }
    return why;
  }

  std::string primary(int depth) {
    if (k_ >= w_.size()) return "rule ends inside its antecedent";
    if (w_[k_] == "(") {
      ++k_;
      std::string why = expression(depth + 1);
      if (!why.empty()) return why;
      if (k_ >= w_.size() || w_[k_] != ")") return "missing ')'";
      ++k_;
      return {};
    }
    const std::string& var = w_[k_++];
    int input = -1;
    for (std::size_t i = 0; i < model_.num_inputs; ++i)
      if (text::name_of(model_.inputs[i].name) == var) input = static_cast<int>(i);
    // An output in an antecedent (chained systems) reads that output's fuzzy output so far.
    bool output = false;
    for (std::size_t o = 0; input < 0 && o < model_.num_outputs; ++o)
      if (text::name_of(model_.outputs[o].name) == var) {
        input = static_cast<int>(o);
        output = true;
      }
    if (input < 0) return "rule names unknown variable '" + var + "'";
    if (!is("is")) return "expected 'is' after '" + var + "'";
    ++k_;
    Token t{output ? Token::Kind::OutputProposition : Token::Kind::Proposition,
            static_cast<std::uint8_t>(input),
            0,
            0,
            {},
            0};
    Hedge h{};
    while (hedge(h)) {
      if (t.num_hedges == fuzzy::kMaxHedges)
        return "more than " + std::to_string(fuzzy::kMaxHedges) + " hedges in one proposition";
      t.hedges[t.num_hedges++] = h;
      ++k_;
      if (h == Hedge::Any) {
        t.term = Token::kAnyTerm;
        tokens_.push_back(t);
        return {};
      }
    }
    if (k_ >= w_.size()) return "rule ends after '" + var + " is'";
    const std::size_t index = static_cast<std::size_t>(input);
    const std::size_t num_terms =
        output ? model_.outputs[index].num_terms : model_.inputs[index].num_terms;
    const auto& term_names =
        output ? model_.outputs[index].term_names : model_.inputs[index].term_names;
    const std::string& term = w_[k_++];
    const int j = find_term(term_names, num_terms, term);
    if (j >= 0) {
      t.term = static_cast<std::uint8_t>(j);
      tokens_.push_back(t);
      return {};
    }
    return "rule names unknown term '" + term + "' of " + (output ? "output" : "input") + " '" +
           var + "'";
  }

  std::string conclusion() {
    if (k_ >= w_.size()) return "rule has no conclusion after 'then'";
    const std::string& var = w_[k_++];
    int output = -1;
    for (std::size_t o = 0; o < model_.num_outputs; ++o)
      if (text::name_of(model_.outputs[o].name) == var) output = static_cast<int>(o);
    if (output < 0) return "rule names unknown output variable '" + var + "'";
    if (!is("is")) return "expected 'is' after '" + var + "'";
    ++k_;
    Conclusion c{static_cast<std::uint8_t>(output), 0, 0, {}, 0};
    Hedge h{};
    while (hedge(h)) {
      if (c.num_hedges == fuzzy::kMaxHedges)
        return "more than " + std::to_string(fuzzy::kMaxHedges) + " hedges in one conclusion";
      c.hedges[c.num_hedges++] = h;
      ++k_;
    }
    if (k_ >= w_.size()) return "rule ends after '" + var + " is'";
    const auto& out = model_.outputs[static_cast<std::size_t>(output)];
    const std::string& term = w_[k_++];
    const int j = find_term(out.term_names, out.num_terms, term);
    if (j >= 0) {
      c.term = static_cast<std::uint8_t>(j);
      for (const Conclusion& other : conclusions_)
        if (other.output == c.output)
          return "output '" + var + "' concluded twice in one rule (not supported)";
      conclusions_.push_back(c);
      return {};
    }
    return "rule names unknown term '" + term + "' of output '" + var + "'";
  }

  // The index of the term named `name` (the first or the last of several), -1 when none is.
  template <class Names>
  int find_term(const Names& names, std::size_t n, const std::string& name) const {
    int found = -1;
    for (std::size_t j = 0; j < n; ++j)
      if (text::name_of(names[j]) == name) {
        found = static_cast<int>(j);
        if (duplicate_ == DuplicateTerm::First) break;
      }
    return found;
  }

  std::vector<std::string> w_;
  Builder& model_;
  bool any_case_;
  DuplicateTerm duplicate_;
  std::size_t k_ = 0;
  double weight_ = 1.0;
  std::vector<Token> tokens_;
  std::vector<Conclusion> conclusions_;
};

std::string hedges_text(const std::array<Hedge, fuzzy::kMaxHedges>& h, std::size_t n) {
  std::string s;
  for (std::size_t k = 0; k < n; ++k)
    s += std::string(fuzzy::to_string(h[k])) + " ";
  return s;
}

}  // namespace

namespace {

std::string unique_name(const fuzzy::Name& raw, std::vector<std::string>& taken) {
  std::string base = text::sanitized(text::name_of(raw));
  if (base.empty()) base = "unnamed";
  if (text::is_reserved(base)) base += "_";
  std::string name = base;
  for (int k = 2;; ++k) {
    bool clash = false;
    for (const auto& t : taken)
      clash = clash || t == name;
    if (!clash) break;
    name = base + "_" + std::to_string(k);
  }
  taken.push_back(name);
  return name;
}

}  // namespace

ExportNames export_names(const Model& m) {
  ExportNames n;
  std::vector<std::string> variables;
  for (std::size_t i = 0; i < m.num_inputs; ++i) {
    n.inputs.push_back(unique_name(m.inputs[i].name, variables));
    std::vector<std::string> terms;
    for (std::size_t t = 0; t < m.inputs[i].num_terms; ++t)
      unique_name(m.inputs[i].term_names[t], terms);
    n.input_terms.push_back(terms);
  }
  for (std::size_t o = 0; o < m.num_outputs; ++o) {
    n.outputs.push_back(unique_name(m.outputs[o].name, variables));
    std::vector<std::string> terms;
    for (std::size_t t = 0; t < m.outputs[o].num_terms; ++t)
      unique_name(m.outputs[o].term_names[t], terms);
    n.output_terms.push_back(terms);
  }
  return n;
}

std::string parse_rule(std::string_view rule_text, Builder& model, std::size_t block, bool any_case,
                       DuplicateTerm duplicate) {
  return Parser(tokenize(rule_text), model, any_case, duplicate).parse(block);
}

std::string write_rule(const Model& m, std::size_t r, const ExportNames& names) {
  const auto& rule = m.rules[r];
  // Rebuild infix text from the postfix tokens; an operand is parenthesised when it is an 'or'
  // under an 'and', or when it is the right operand of the same connective (the grammar is
  // left-associative).
  struct Piece {
    std::string text;
    Token::Kind kind;
  };
  std::vector<Piece> stack;
  for (std::size_t k = 0; k < rule.num_tokens; ++k) {
    const Token& t = m.tokens[rule.first_token + k];
    const bool output = t.kind == Token::Kind::OutputProposition;
    if (t.kind == Token::Kind::Proposition || output) {
      std::string s = (output ? names.outputs : names.inputs)[t.input] + " is " +
                      hedges_text(t.hedges, t.num_hedges);
      if (t.term != Token::kAnyTerm)
        s += (output ? names.output_terms : names.input_terms)[t.input][t.term];
      while (!s.empty() && s.back() == ' ')
        s.pop_back();
      stack.push_back({s, Token::Kind::Proposition});
      continue;
    }
    Piece b = stack.back();
    stack.pop_back();
    Piece a = stack.back();
    stack.pop_back();
    const bool is_and = t.kind == Token::Kind::And;
    if (is_and && a.kind == Token::Kind::Or) a.text = "(" + a.text + ")";
    if (b.kind != Token::Kind::Proposition && (is_and || b.kind == t.kind))
      b.text = "(" + b.text + ")";
    stack.push_back({a.text + (is_and ? " and " : " or ") + b.text, t.kind});
  }
  std::string s = "if " + (stack.empty() ? std::string() : stack.back().text) + " then ";
  for (std::size_t k = 0; k < rule.num_conclusions; ++k) {
    const Conclusion& c = m.conclusions[rule.first_conclusion + k];
    s += (k ? " and " : "") + names.outputs[c.output] + " is " +
         hedges_text(c.hedges, c.num_hedges) + names.output_terms[c.output][c.term];
  }
  if (rule.weight != 1.0) s += " with " + text::format_number(rule.weight);
  return s;
}

}  // namespace fuzzypid::rulefile::rules
