#include "formula.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>

#include "text.hpp"

namespace fuzzypid::rulefile::formula {

namespace {

using fuzzy::FormulaOp;
using Step = fuzzy::FormulaStep<double>;

// fuzzylite 8's FunctionFactory: operators with their precedence (higher binds tighter) and
// associativity (right: 1, left: -1); functions all at precedence 100, left.
struct Element {
  const char* name;
  FormulaOp op;
  bool function;
  int precedence;
  int associativity;
};

constexpr Element kElements[] = {
    {"!", FormulaOp::Not, false, 100, 1},       {"~", FormulaOp::Negate, false, 100, 1},
    {"^", FormulaOp::Power, false, 90, 1},      {"**", FormulaOp::Power, false, 90, 1},
    {".-", FormulaOp::Negate, false, 90, 1},    {".+", FormulaOp::Plus, false, 90, 1},
    {"*", FormulaOp::Multiply, false, 80, -1},  {"/", FormulaOp::Divide, false, 80, -1},
    {"%", FormulaOp::Modulo, false, 80, -1},    {"+", FormulaOp::Add, false, 70, -1},
    {"-", FormulaOp::Subtract, false, 70, -1},  {"and", FormulaOp::And, false, 60, -1},
    {"or", FormulaOp::Or, false, 50, -1},       {"gt", FormulaOp::Gt, true, 100, -1},
    {"ge", FormulaOp::Ge, true, 100, -1},       {"eq", FormulaOp::Eq, true, 100, -1},
    {"neq", FormulaOp::Neq, true, 100, -1},     {"le", FormulaOp::Le, true, 100, -1},
    {"lt", FormulaOp::Lt, true, 100, -1},       {"min", FormulaOp::Min, true, 100, -1},
    {"max", FormulaOp::Max, true, 100, -1},     {"acos", FormulaOp::Acos, true, 100, -1},
    {"asin", FormulaOp::Asin, true, 100, -1},   {"atan", FormulaOp::Atan, true, 100, -1},
    {"ceil", FormulaOp::Ceil, true, 100, -1},   {"cos", FormulaOp::Cos, true, 100, -1},
    {"cosh", FormulaOp::Cosh, true, 100, -1},   {"exp", FormulaOp::Exp, true, 100, -1},
    {"abs", FormulaOp::Abs, true, 100, -1},     {"fabs", FormulaOp::Abs, true, 100, -1},
    {"floor", FormulaOp::Floor, true, 100, -1}, {"log", FormulaOp::Log, true, 100, -1},
    {"log10", FormulaOp::Log10, true, 100, -1}, {"round", FormulaOp::Round, true, 100, -1},
    {"sin", FormulaOp::Sin, true, 100, -1},     {"sinh", FormulaOp::Sinh, true, 100, -1},
    {"sqrt", FormulaOp::Sqrt, true, 100, -1},   {"tan", FormulaOp::Tan, true, 100, -1},
    {"tanh", FormulaOp::Tanh, true, 100, -1},   {"log1p", FormulaOp::Log1p, true, 100, -1},
    {"acosh", FormulaOp::Acosh, true, 100, -1}, {"asinh", FormulaOp::Asinh, true, 100, -1},
    {"atanh", FormulaOp::Atanh, true, 100, -1}, {"pow", FormulaOp::Power, true, 100, -1},
    {"atan2", FormulaOp::Atan2, true, 100, -1}, {"fmod", FormulaOp::Fmod, true, 100, -1},
    {"pi", FormulaOp::Pi, true, 100, -1},
};

const Element* find_element(std::string_view token) {
  for (const Element& e : kElements)
    if (token == e.name) return &e;
  return nullptr;
}

// fuzzylite 8's Function.format_infix, then split: the operators (but `and`, `or`), parentheses
// and commas are tokens of their own wherever they stand, the longest first (".-" before "-");
// everything else is split at blanks.
std::vector<std::string_view> tokens_of(std::string_view s) {
  static constexpr std::string_view kSymbols[] = {"**", ".-", ".+", "!", "~", "^", "*",
                                                  "/",  "%",  "+",  "-", "(", ")", ","};
  std::vector<std::string_view> out;
  std::size_t word = std::string_view::npos;
  const auto end_word = [&](std::size_t k) {
    if (word != std::string_view::npos) out.push_back(s.substr(word, k - word));
    word = std::string_view::npos;
  };
  for (std::size_t k = 0; k < s.size();) {
    std::string_view symbol;
    for (std::string_view sym : kSymbols)
      if (s.substr(k, sym.size()) == sym) {
        symbol = sym;
        break;
      }
    if (!symbol.empty()) {
      end_word(k);
      out.push_back(symbol);
      k += symbol.size();
    } else if (s[k] == ' ' || s[k] == '\t' || s[k] == '\r' || s[k] == '\n') {
      end_word(k);
      ++k;
    } else {
      if (word == std::string_view::npos) word = k;
      ++k;
    }
  }
  end_word(s.size());
  return out;
}

// A decimal number as Python's float() reads it, without what the tokens cannot hold (signs are
// operators) or what fuzzypid does not read (inf, nan, digit separators '_').
bool number(std::string_view t, double& value) {
  std::size_t k = 0;
  std::size_t digits = 0;
  while (k < t.size() && t[k] >= '0' && t[k] <= '9')
    ++k, ++digits;
  if (k < t.size() && t[k] == '.') {
    ++k;
    while (k < t.size() && t[k] >= '0' && t[k] <= '9')
      ++k, ++digits;
  }
  if (digits == 0) return false;
  if (k < t.size() && (t[k] == 'e' || t[k] == 'E')) {
    ++k;
    const std::size_t start = k;
    while (k < t.size() && t[k] >= '0' && t[k] <= '9')
      ++k;
    if (k == start) return false;
  }
  return k == t.size() && text::parse_number(t, value);
}

}  // namespace

std::string compile(std::string_view text_in, bool x_allowed, Builder& model,
                    fuzzy::Term<double>& term) {
  const std::string_view formula_text = text::trim(text_in);
  if (formula_text.empty()) return "a Function term needs a formula";
  if (formula_text.size() > kMaxFormulaLength)
    return "formula longer than " + std::to_string(kMaxFormulaLength) + " bytes";
  for (std::size_t i = 0; i < model.num_inputs; ++i)
    if (text::name_of(model.inputs[i].name) == "x")
      return "an input named 'x' hides the formula's x (fuzzylite refuses it too)";
  for (std::size_t o = 0; o < model.num_outputs; ++o)
    if (text::name_of(model.outputs[o].name) == "x")
      return "an output named 'x' hides the formula's x (fuzzylite refuses it too)";

  // fuzzylite 8's Function.infix_to_postfix (a shunting-yard): `queue` is the postfix result,
  // `stack` holds elements and open parentheses (nullptr).
  struct Item {
    const Element* element = nullptr;
    std::string_view operand;
  };
  std::vector<Item> queue;
  std::vector<const Element*> stack;
  const auto unbalanced = [&] {
    return "mismatching parentheses in formula '" + std::string(formula_text) + "'";
  };
  for (std::string_view token : tokens_of(formula_text)) {
    const Element* element = find_element(token);
    if (element == nullptr && token != "(" && token != ")" && token != ",") {
      queue.push_back({nullptr, token});
    } else if (element != nullptr && element->function) {
      stack.push_back(element);
    } else if (token == ",") {
      while (!stack.empty() && stack.back() != nullptr) {
        queue.push_back({stack.back(), {}});
        stack.pop_back();
      }
      if (stack.empty())
        return "',' outside the parentheses of a function in formula '" +
               std::string(formula_text) + "'";
    } else if (element != nullptr) {
      while (!stack.empty() && stack.back() != nullptr) {
        const Element* top = stack.back();
        if ((element->associativity < 0 && element->precedence <= top->precedence) ||
            (element->associativity > 0 && element->precedence < top->precedence)) {
          queue.push_back({top, {}});
          stack.pop_back();
        } else {
          break;
        }
      }
      stack.push_back(element);
    } else if (token == "(") {
      stack.push_back(nullptr);
    } else {  // ")"
      while (!stack.empty() && stack.back() != nullptr) {
        queue.push_back({stack.back(), {}});
        stack.pop_back();
      }
      if (stack.empty()) return unbalanced();
      stack.pop_back();
      if (!stack.empty() && stack.back() != nullptr && stack.back()->function) {
        queue.push_back({stack.back(), {}});
        stack.pop_back();
      }
    }
  }
  while (!stack.empty()) {
    if (stack.back() == nullptr) return unbalanced();
    queue.push_back({stack.back(), {}});
    stack.pop_back();
  }

  // fuzzylite 8's Function.parse: each element takes its operands from the values before it.
  std::vector<Step> steps;
  std::size_t depth = 0;
  for (const Item& item : queue) {
    Step step;
    if (item.element != nullptr) {
      step.op = item.element->op;
      const std::size_t arity = fuzzy::formula_arity(step.op);
      if (arity > depth)
        return "'" + std::string(item.element->name) + "' takes " + std::to_string(arity) +
               (arity == 1 ? " operand" : " operands") + " but has " + std::to_string(depth) +
               " in formula '" + std::string(formula_text) +
               "' (a leading minus is written .- or ~)";
      depth -= arity;
    } else if (item.operand == "x") {
      if (!x_allowed)
        return "x in an output's formula is the rule's activation degree, where fuzzylite 6 and 8 "
               "differ (per rule; per term after aggregation): not supported, use the inputs' "
               "names";
      step.op = FormulaOp::X;
    } else if (number(item.operand, step.value)) {
      step.op = FormulaOp::Number;
    } else {
      bool found = false;
      for (std::size_t i = 0; i < model.num_inputs && !found; ++i)
        if (text::name_of(model.inputs[i].name) == item.operand) {
          step.op = FormulaOp::Input;
          step.input = static_cast<std::uint8_t>(i);
          found = true;
        }
      for (std::size_t o = 0; o < model.num_outputs && !found; ++o)
        if (text::name_of(model.outputs[o].name) == item.operand)
          return "formula names output '" + std::string(item.operand) +
                 "', whose value fuzzylite takes from the order of evaluation (the previous "
                 "evaluation's, NaN before the first, this one's for outputs defuzzified "
                 "earlier): not supported, formulas read x and the inputs";
      if (!found)
        return "unknown name '" + std::string(item.operand) + "' in formula '" +
               std::string(formula_text) +
               "' (not a number, operator, function, x or the name of an input)";
    }
    ++depth;
    if (depth > fuzzy::kMaxFormulaDepth)
      return "formula '" + std::string(formula_text) + "' needs more than " +
             std::to_string(fuzzy::kMaxFormulaDepth) + " values at once (nest it less deeply)";
    steps.push_back(step);
  }
  if (depth != 1)
    return "invalid formula '" + std::string(formula_text) + "': " + std::to_string(depth) +
           " values where one expression was expected";
  if (model.num_steps + steps.size() > Builder::Capacity::steps)
    return "formulas exceed the capacity (" + std::to_string(Builder::Capacity::steps) +
           " steps in all)";
  term = fuzzy::Term<double>{};
  term.shape = fuzzy::Shape::Function;
  term.first = static_cast<std::uint32_t>(model.num_steps);
  term.count = static_cast<std::uint32_t>(steps.size());
  for (const Step& s : steps)
    model.steps[model.num_steps++] = s;
  return {};
}

bool compile_all(const std::vector<Pending>& pending, Builder& model, LoadError& error) {
  for (const Pending& p : pending) {
    fuzzy::Term<double> term;
    const std::string why = compile(p.text, p.input, model, term);
    if (!why.empty()) {
      error.line = p.line;
      error.message = "term '" + p.name + "': " + why;
      return false;
    }
    if (p.input) {
      model.inputs[p.variable].terms[p.term] = term;
    } else {
      auto& t = model.outputs[p.variable].terms[p.term];
      t.kind = fuzzy::OutputTermKind::Function;
      t.membership = term;
    }
  }
  return true;
}

std::string write(const fuzzy::Term<double>& term, const Model& model) {
  if (term.shape != fuzzy::Shape::Function ||
      static_cast<std::size_t>(term.first) + term.count > model.num_steps)
    return {};
  std::vector<std::string> values;
  for (std::size_t k = 0; k < term.count; ++k) {
    const Step& s = model.steps[term.first + k];
    const std::size_t arity = fuzzy::formula_arity(s.op);
    if (values.size() < arity) return {};
    std::string a, b;
    if (arity >= 1) {
      b = std::move(values.back());
      values.pop_back();
    }
    if (arity == 2) {
      a = std::move(values.back());
      values.pop_back();
    }
    const char* name = nullptr;
    bool function = true;
    for (const Element& e : kElements)
      if (e.op == s.op && name == nullptr) {
        name = e.name;
        function = e.function;
      }
    if (s.op == FormulaOp::Negate) name = "~";  // fuzzylite 6 reads ~, not .-
    std::string v;
    if (s.op == FormulaOp::Number) {
      if (!std::isfinite(s.value)) return {};
      // Fixed notation: an exponent's sign would be read as an operator.
      char buffer[400];
      const auto r = std::to_chars(buffer, buffer + sizeof buffer, std::fabs(s.value),
                                   std::chars_format::fixed);
      if (r.ec != std::errc{}) return {};
      v.assign(buffer, r.ptr);
      if (std::signbit(s.value)) v = "(~ " + v + ")";
    } else if (s.op == FormulaOp::X) {
      v = "x";
    } else if (s.op == FormulaOp::Input) {
      if (s.input >= model.num_inputs) return {};
      v = std::string(text::name_of(model.inputs[s.input].name));
    } else if (arity == 0) {
      v = name;
    } else if (function) {
      v = std::string(name) + "(" + (arity == 2 ? a + ", " + b : b) + ")";
    } else {
      v = "(" + (arity == 2 ? a + " " + name + " " + b : std::string(name) + " " + b) + ")";
    }
    values.push_back(std::move(v));
  }
  if (values.size() != 1) return {};
  std::string s = std::move(values.back());
  // The outermost parentheses are not needed.
  if (s.size() >= 2 && s.front() == '(' && s.back() == ')') {
    int open = 0;
    bool outer = true;
    for (std::size_t k = 0; k + 1 < s.size() && outer; ++k) {
      open += s[k] == '(' ? 1 : s[k] == ')' ? -1 : 0;
      outer = open > 0;
    }
    if (outer) s = s.substr(1, s.size() - 2);
  }
  return s;
}

}  // namespace fuzzypid::rulefile::formula
