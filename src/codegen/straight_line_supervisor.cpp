#include "straight_line_supervisor.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "export_rule_base.hpp"
#include "fuzzypid/fuzzy/operators.hpp"

namespace fuzzypid::codegen {

namespace {

using Model = fuzzy::EngineModel<double>;
using fuzzy::Hedge;
using fuzzy::Shape;
using fuzzy::Token;

std::string num(std::size_t n) {
  return std::to_string(n);
}

std::string lit(double v) {
  return scalar_literal(v);
}

// A name as it may stand in a // comment of the generated code (a name may hold any byte but
// NUL, so a line break would end the comment).
std::string name(const fuzzy::Name& n) {
  std::string s = n.data();
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return s;
}

// The call of fuzzy::Term::operator() for `t` at `x`, written for its shape (the same function
// with the same arguments, so the same result).
std::string membership_call(const fuzzy::Term<double>& t, const std::string& x) {
  const auto& p = t.p;
  const std::string h = lit(t.height);
  const auto two = [&](const char* f) {
    return std::string("fz::shape::") + f + "(" + lit(p[0]) + ", " + lit(p[1]) + ", " + h + ", " +
           x + ")";
  };
  const auto four = [&](const char* f) {
    return std::string("fz::shape::") + f + "(" + lit(p[0]) + ", " + lit(p[1]) + ", " + lit(p[2]) +
           ", " + lit(p[3]) + ", " + h + ", " + x + ")";
  };
  switch (t.shape) {
    case Shape::Triangle:
      return "fz::shape::triangle(" + lit(p[0]) + ", " + lit(p[1]) + ", " + lit(p[2]) + ", " + h +
             ", " + x + ")";
    case Shape::Trapezoid:
      return four("trapezoid");
    case Shape::LeftShoulder:
      return "fz::LeftShoulder<Scalar>{" + lit(p[0]) + ", " + lit(p[1]) + "}(" + x + ")";
    case Shape::RightShoulder:
      return "fz::RightShoulder<Scalar>{" + lit(p[0]) + ", " + lit(p[1]) + "}(" + x + ")";
    case Shape::Singleton:
      return "fz::Singleton<Scalar>{" + lit(p[0]) + "}(" + x + ")";
    case Shape::Gaussian:
      return two("gaussian");
    case Shape::Bell:
      return "fz::shape::bell(" + lit(p[2]) + ", " + lit(p[0]) + ", " + lit(p[1]) + ", " + h +
             ", " + x + ")";
    case Shape::Rectangle:
      return two("rectangle");
    case Shape::GaussianProduct:
      return four("gaussian_product");
    case Shape::PiShape:
      return four("pi_shape");
    case Shape::SShape:
      return two("s_shape");
    case Shape::ZShape:
      return two("z_shape");
    case Shape::Sigmoid:
      return two("sigmoid");
    case Shape::SigmoidDifference:
      return four("sigmoid_difference");
    case Shape::SigmoidProduct:
      return four("sigmoid_product");
    case Shape::Ramp:
      return two("ramp");
    case Shape::Cosine:
      return two("cosine");
    case Shape::Concave:
      return two("concave");
    case Shape::Spike:
      return two("spike");
    case Shape::Binary:
      return two("binary");
    case Shape::Discrete:
      return "fz::shape::discrete(kPoints + " + num(2 * t.first) + ", " + num(t.count) + ", " + h +
             ", " + x + ")";
    case Shape::Arc:
      return two("arc");
    case Shape::SemiEllipse:
      return two("semi_ellipse");
    case Shape::Function:  // a formula: interpreted (fuzzy/formula.hpp)
      return {};
  }
  return {};
}

bool shape_known(Shape s) {
  return !membership_call(fuzzy::Term<double>::make(s, 0.0), "x").empty();
}

template <class Enum>
std::string enum_name(const char* type, Enum e) {
  return "static_cast<fz::" + std::string(type) + ">(" + std::to_string(static_cast<unsigned>(e)) +
         ")";
}

std::string hedge_call(Hedge h, const std::string& x) {
  return "fz::apply(" + enum_name("Hedge", h) + ", " + x + ")";
}

// The hedges right to left on x (engine_detail::hedge_right_to_left).
std::string hedged(const std::array<Hedge, fuzzy::kMaxHedges>& hedges, std::size_t n,
                   std::string x) {
  for (std::size_t k = n; k-- > 0;)
    x = hedge_call(hedges[k], x);
  return x;
}

std::string tnorm(fuzzy::TNorm op, const std::string& a, const std::string& b) {
  switch (op) {
    case fuzzy::TNorm::Minimum:
      return "fuzzypid::detail::min(" + a + ", " + b + ")";
    case fuzzy::TNorm::Product:
      return "(" + a + " * " + b + ")";
    default:
      return "fz::apply(" + enum_name("TNorm", op) + ", " + a + ", " + b + ")";
  }
}

std::string snorm(fuzzy::SNorm op, const std::string& a, const std::string& b) {
  if (op == fuzzy::SNorm::Maximum) return "fuzzypid::detail::max(" + a + ", " + b + ")";
  return "fz::apply(" + enum_name("SNorm", op) + ", " + a + ", " + b + ")";
}

const char* comparison(fuzzy::Comparison c) {
  return fuzzypid::name_of(fuzzy::kComparisonNames, c);
}

// A proposition as it is computed: which input and term, and the hedges.
struct Proposition {
  std::size_t input = 0;
  std::size_t term = 0;
  std::size_t num_hedges = 0;
  std::array<Hedge, fuzzy::kMaxHedges> hedges{};
  unsigned power_tenths = 0;
  bool operator<(const Proposition& o) const {
    if (input != o.input) return input < o.input;
    if (term != o.term) return term < o.term;
    if (num_hedges != o.num_hedges) return num_hedges < o.num_hedges;
    if (power_tenths != o.power_tenths) return power_tenths < o.power_tenths;
    return hedges < o.hedges;
  }
};

Proposition proposition_of(const Token& t) {
  Proposition p{t.input, t.term, t.num_hedges, {}, t.power_tenths};
  for (std::size_t k = 0; k < t.num_hedges; ++k)
    p.hedges[k] = t.hedges[k];
  // Any as the last hedge makes the term irrelevant (engine_detail::proposition).
  if (p.num_hedges > 0 && p.hedges[p.num_hedges - 1] == Hedge::Any) {
    p.term = Token::kAnyTerm;
    p.power_tenths = 0;
  }
  return p;
}

// The value of a proposition (engine_detail::proposition): `any` is 1 before the other hedges;
// else the term's degree, raised to Octave's power dd/10, then the hedges right to left.
std::string proposition_value(const Proposition& p, const std::vector<std::string>& membership,
                              std::size_t stride) {
  if (p.term == Token::kAnyTerm) return hedged(p.hedges, p.num_hedges - 1, "Scalar(1)");
  std::string mu = membership[p.input * stride + p.term];
  if (p.power_tenths != 0)
    mu = "std::pow(" + mu + ", static_cast<Scalar>(" + num(p.power_tenths) + ") / Scalar(10))";
  return hedged(p.hedges, p.num_hedges, mu);
}

bool pure_conjunction(const Model& m, const fuzzy::Rule<double>& rule) {
  for (std::size_t k = 0; k < rule.num_tokens; ++k)
    if (m.tokens[rule.first_token + k].kind == Token::Kind::Or) return false;
  return true;
}

}  // namespace

std::string straight_line_refusal(const Model& m) {
  if (m.chained) return "a rule tests an output (a chained system)";
  if (m.has_disabled_variables()) return "a variable is disabled";
  for (std::size_t i = 0; i < m.num_inputs; ++i)
    for (std::size_t t = 0; t < m.inputs[i].num_terms; ++t)
      if (!shape_known(m.inputs[i].terms[t].shape))
        return std::string("input ") + name(m.inputs[i].name) + " has a term of a shape the " +
               "generator does not write";
  for (std::size_t b = 0; b < m.num_blocks; ++b) {
    const auto a = m.blocks[b].activation;
    if (a != fuzzy::ActivationMethod::General && a != fuzzy::ActivationMethod::Threshold)
      return std::string("rule block ") + num(b + 1) + " activates by " +
             fuzzypid::name_of(fuzzy::kActivationNames, a) + " (General and Threshold only)";
  }
  for (std::size_t o = 0; o < m.num_outputs; ++o) {
    const auto& out = m.outputs[o];
    const std::string which = std::string("output ") + name(out.name);
    if (!fuzzy::is_sugeno(out.defuzzifier))
      return which + " is not Takagi-Sugeno (weighted average or sum)";
    if (out.merge_equal_singletons) return which + " merges equal singletons (Octave's .fis)";
    if (out.group_by_term)
      return which + " aggregates each term's activations first (fuzzylite 8's weighted output)";
    for (std::size_t t = 0; t < out.num_terms; ++t) {
      if (out.terms[t].kind == fuzzy::OutputTermKind::Membership)
        return which + " has a Tsukamoto term";
      if (out.terms[t].kind != fuzzy::OutputTermKind::Constant &&
          out.terms[t].kind != fuzzy::OutputTermKind::Linear)
        return which + " has a Function term (a formula)";
    }
  }
  return {};
}

std::string straight_line_supervisor(const Model& m, const SupervisorBinding& binding) {
  std::string body;
  const auto line = [&](int indent, const std::string& s) {
    body += std::string(static_cast<std::size_t>(indent), ' ') + s + "\n";
  };

  // Inputs: refused when not finite, then locked into the range, then every term's degree.
  std::size_t stride = 1;
  for (std::size_t i = 0; i < m.num_inputs; ++i)
    stride = std::max(stride, m.inputs[i].num_terms);
  std::vector<std::string> x(m.num_inputs);
  std::vector<std::string> membership(m.num_inputs * stride);
  for (std::size_t i = 0; i < m.num_inputs; ++i) {
    const auto& in = m.inputs[i];
    x[i] = "x" + num(i);
    const std::string given = "in[" + num(i) + "]";
    line(4, "const Scalar " + x[i] + " = " +
                (in.lock_range ? "fuzzypid::detail::clamp(" + given + ", " + lit(in.min) + ", " +
                                     lit(in.max) + ")"
                               : given) +
                ";  // " + name(in.name));
  }
  // Only the terms some rule reads (the others cannot change an output).
  std::map<Proposition, std::string> propositions;
  std::vector<bool> term_used(m.num_inputs * stride, false);
  for (std::size_t k = 0; k < m.num_tokens; ++k) {
    const Token& t = m.tokens[k];
    if (t.kind != Token::Kind::Proposition) continue;
    const Proposition p = proposition_of(t);
    if (p.term != Token::kAnyTerm) term_used[p.input * stride + p.term] = true;
    propositions.emplace(p, std::string());
  }
  for (std::size_t i = 0; i < m.num_inputs; ++i)
    for (std::size_t t = 0; t < m.inputs[i].num_terms; ++t) {
      if (!term_used[i * stride + t]) continue;
      const std::string mu = "mu" + num(i) + "_" + num(t);
      membership[i * stride + t] = mu;
      line(4, "const Scalar " + mu + " = " + membership_call(m.inputs[i].terms[t], x[i]) +
                  ";  // " + name(m.inputs[i].name) + " is " + name(m.inputs[i].term_names[t]));
    }
  std::size_t next = 0;
  for (auto& [p, var] : propositions) {
    const std::string value = proposition_value(p, membership, stride);
    if (p.term != Token::kAnyTerm && value == membership[p.input * stride + p.term]) {
      var = value;
      continue;
    }
    var = "p" + num(next++);
    line(4, "const Scalar " + var + " = " + value + ";");
  }

  // Accumulators: one sum per output, and one weight sum and fired flag per distinct stream of
  // degrees (outputs concluded on by the same rules with the same degrees share them).
  struct Step {
    std::size_t rule;
    std::string degree;
  };
  std::vector<std::vector<Step>> stream(m.num_outputs);
  std::vector<std::vector<std::string>> degree_of(m.num_rules);
  for (std::size_t r = 0; r < m.num_rules; ++r) {
    const auto& rule = m.rules[r];
    bool running_is_w = true;
    for (std::size_t k = 0; k < rule.num_conclusions; ++k) {
      const auto& c = m.conclusions[rule.first_conclusion + k];
      std::string d;
      if (c.power_tenths == 0 && c.num_hedges == 0 && running_is_w)
        d = "w";
      else
        d = "d" + num(k);
      if (c.power_tenths == 0 && c.num_hedges > 0) running_is_w = false;
      degree_of[r].push_back(d);
      stream[c.output].push_back({r, d});
    }
  }
  std::vector<std::size_t> weights_of(m.num_outputs);
  std::vector<std::size_t> owner;  // the first output of each distinct stream
  for (std::size_t o = 0; o < m.num_outputs; ++o) {
    std::size_t s = 0;
    for (; s < owner.size(); ++s) {
      const auto& a = stream[owner[s]];
      const auto& b = stream[o];
      bool same = a.size() == b.size();
      for (std::size_t k = 0; same && k < a.size(); ++k)
        same = a[k].rule == b[k].rule && a[k].degree == b[k].degree;
      if (same) break;
    }
    if (s == owner.size()) owner.push_back(o);
    weights_of[o] = s;
  }
  // A weighted sum reads no weights.
  std::vector<bool> needs_weights(owner.size(), false);
  for (std::size_t o = 0; o < m.num_outputs; ++o)
    if (m.outputs[o].defuzzifier == fuzzy::Defuzzifier::WeightedAverage)
      needs_weights[weights_of[o]] = true;
  for (std::size_t o = 0; o < m.num_outputs; ++o)
    if (!stream[o].empty())
      line(4, "Scalar sum" + num(o) + " = Scalar(0);  // " + name(m.outputs[o].name));
  for (std::size_t s = 0; s < owner.size(); ++s) {
    if (stream[owner[s]].empty()) continue;
    if (needs_weights[s]) line(4, "Scalar weights" + num(s) + " = Scalar(0);");
    line(4, "bool fired" + num(s) + " = false;");
  }

  // Rules, block by block, each block's in file order (the order the engine fires them in).
  for (std::size_t b = 0; b < m.num_blocks; ++b) {
    const auto& block = m.blocks[b];
    // A run of consecutive rules is opened by the same conjunct: when it is 0 no rule of the run
    // has a strength above 0 (min(0, y) <= 0 for a Minimum conjunction and a weight >= 0), so
    // the run is skipped.
    std::string open_guard;
    for (std::size_t r = 0; r < m.num_rules; ++r) {
      const auto& rule = m.rules[r];
      if (rule.block != b) continue;
      // The antecedent, evaluated as rule_strength's postfix stack.
      std::vector<std::string> stack;
      std::vector<std::string> text_stack;
      for (std::size_t k = 0; k < rule.num_tokens; ++k) {
        const Token& t = m.tokens[rule.first_token + k];
        if (t.kind == Token::Kind::And || t.kind == Token::Kind::Or) {
          const std::string rhs = stack.back();
          stack.pop_back();
          stack.back() = t.kind == Token::Kind::And ? tnorm(block.conjunction, stack.back(), rhs)
                                                    : snorm(block.disjunction, stack.back(), rhs);
          const std::string trhs = text_stack.back();
          text_stack.pop_back();
          text_stack.back() = "(" + text_stack.back() +
                              (t.kind == Token::Kind::And ? " and " : " or ") + trhs + ")";
        } else {
          const Proposition p = proposition_of(t);
          stack.push_back(propositions.at(p));
          std::string words = std::string(name(m.inputs[t.input].name)) + " is";
          for (std::size_t h = 0; h < t.num_hedges; ++h)
            words += std::string(" ") + fuzzy::kHedgeNames[static_cast<unsigned>(t.hedges[h])];
          if (p.term != Token::kAnyTerm)
            words += std::string(" ") + name(m.inputs[t.input].term_names[t.term]);
          text_stack.push_back(words);
        }
      }
      std::string strength = stack.empty() ? "Scalar(0)" : stack.back();
      if (!(rule.weight == 1.0)) strength = lit(rule.weight) + " * " + strength;
      std::string guard;
      if (block.conjunction == fuzzy::TNorm::Minimum && rule.num_tokens > 0 &&
          pure_conjunction(m, rule) && rule.weight >= 0.0 &&
          m.tokens[rule.first_token].kind == Token::Kind::Proposition)
        guard = propositions.at(proposition_of(m.tokens[rule.first_token]));
      if (guard != open_guard) {
        if (!open_guard.empty()) line(4, "}");
        if (!guard.empty()) line(4, "if (" + guard + " > Scalar(0)) {");
        open_guard = guard;
      }
      const int ind = open_guard.empty() ? 4 : 6;
      std::string then;
      for (std::size_t k = 0; k < rule.num_conclusions; ++k) {
        const auto& c = m.conclusions[rule.first_conclusion + k];
        then += std::string(k ? ", " : "") + name(m.outputs[c.output].name) + " is " +
                name(m.outputs[c.output].term_names[c.term]);
      }
      line(ind, "{  // rule " + num(r + 1) + ": if " +
                    (text_stack.empty() ? std::string() : text_stack.back()) + " then " + then);
      line(ind + 2, "const Scalar w = " + strength + ";");
      std::string fires = "w > Scalar(0)";
      if (block.activation == fuzzy::ActivationMethod::Threshold)
        fires += std::string(" && w ") + comparison(block.comparison) + " static_cast<Scalar>(" +
                 lit(block.threshold) + ")";
      line(ind + 2, "if (" + fires + ") {");
      const int in2 = ind + 4;
      std::string running = "w";
      bool declared_running = false;
      for (std::size_t k = 0; k < rule.num_conclusions; ++k) {
        const auto& c = m.conclusions[rule.first_conclusion + k];
        const std::string& d = degree_of[r][k];
        // engine_detail::conclusion_degree
        if (c.power_tenths != 0) {
          line(in2, "const Scalar " + d + " = " +
                        hedged(c.hedges, c.num_hedges,
                               "std::pow(w, Scalar(1) / (static_cast<Scalar>(" +
                                   num(c.power_tenths) + ") / Scalar(10)))") +
                        ";");
        } else if (d != "w") {
          if (c.num_hedges > 0) {
            if (!declared_running) {
              line(in2, "Scalar running = w;");
              declared_running = true;
              running = "running";
            }
            line(in2, "running = " + hedged(c.hedges, c.num_hedges, "running") + ";");
          }
          line(in2, "const Scalar " + d + " = " + running + ";");
        }
        const auto& out = m.outputs[c.output];
        const auto& term = out.terms[c.term];
        std::string z;
        bool zero = false;
        if (term.kind == fuzzy::OutputTermKind::Constant) {
          z = lit(term.coefficients[0]);
          // d * 0 adds 0 to a sum that is never -0: nothing changes, for a finite degree.
          zero = term.coefficients[0] == 0.0 && d == "w";
        } else {  // Linear (straight_line_refusal admits no other kind): sugeno_value
          z = "Scalar(0)";
          for (std::size_t i = 0; i < m.num_inputs; ++i)
            z = "(" + z + " + " + lit(term.coefficients[i]) + " * " + x[i] + ")";
          z = "(" + z + " + " + lit(term.coefficients[m.num_inputs]) + ")";
        }
        if (!zero) line(in2, "sum" + num(c.output) + " += " + d + " * " + z + ";");
        const std::size_t s = weights_of[c.output];
        if (owner[s] == c.output) {
          if (needs_weights[s]) line(in2, "weights" + num(s) + " += " + d + ";");
          line(in2, "fired" + num(s) + " = true;");
        }
      }
      line(ind + 2, "}");
      line(ind, "}");
    }
    if (!open_guard.empty()) line(4, "}");
  }

  // Defuzzification and the fallbacks of evaluate_with, output by output.
  line(4, "fuzzypid::Status status = fuzzypid::Status::Ok;");
  line(4, "Scalar out[" + num(m.num_outputs) + "] = {};");
  for (std::size_t o = 0; o < m.num_outputs; ++o) {
    const auto& out = m.outputs[o];
    const std::string so = num(o);
    const std::string s = num(weights_of[o]);
    const bool any = !stream[o].empty();
    line(4, "{  // " + std::string(name(out.name)));
    const std::string fallback = out.lock_previous
                                     ? "ws.previous[" + so + "] == ws.previous[" + so +
                                           "] ? ws.previous[" + so + "] : " + lit(out.default_value)
                                     : lit(out.default_value);
    const std::string value = out.defuzzifier == fuzzy::Defuzzifier::WeightedAverage
                                  ? "sum" + so + " / weights" + s
                                  : "sum" + so;
    if (any)
      line(6, "Scalar y = fired" + s + " ? " + value + " : " + fallback + ";");
    else
      line(6, "Scalar y = " + fallback + ";  // no rule concludes on it");
    if (out.lock_range)
      line(6, "if (y == y) y = fuzzypid::detail::clamp(y, " + lit(out.min) + ", " + lit(out.max) +
                  ");");
    if (out.lock_previous)
      line(6, "if (fuzzypid::detail::is_finite(y)) ws.previous[" + so + "] = y;");
    line(6, "if (y != y) {");
    line(8, "y = Scalar(0);");
    line(8, "status = fuzzypid::Status::NoRuleFired;");
    line(6, "}");
    line(6, "out[" + so + "] = y;");
    line(4, "}");
  }
  for (std::size_t g = 0; g < 3; ++g)
    line(4, "delta[" + num(g) + "] = out[" + num(binding.output_of[g]) + "];");
  line(4, "return status;");

  bool lock_previous = false;
  for (std::size_t o = 0; o < m.num_outputs; ++o)
    lock_previous = lock_previous || m.outputs[o].lock_previous;

  std::string h;
  h += "// The supervisor FuzzyPid calls (the concept of fuzzypid/supervisor/supervisor.hpp), as\n"
       "// straight-line code generated from the rule base: what fuzzy::evaluate computes on\n"
       "// kRuleBase, bit for bit, with no loop over the model. A run of rules opened by a\n"
       "// conjunct of degree 0 is skipped (none of its rules can fire).\n";
  h += "template <class Scalar>\nclass Supervisor {\n public:\n";
  if (lock_previous) {
    h += "  // The outputs' last finite values (lock-previous), NaN before the first.\n";
    h += "  struct Workspace {\n    std::array<Scalar, " + num(m.num_outputs) +
         "> previous;\n  };\n";
    std::string nans;
    for (std::size_t o = 0; o < m.num_outputs; ++o)
      nans += std::string(o ? ", " : "") + "std::numeric_limits<Scalar>::quiet_NaN()";
    h += "  Workspace make_workspace() const noexcept { return {{" + nans + "}}; }\n\n";
  } else {
    h += "  struct Workspace {};  // no per-joint state\n";
    h += "  Workspace make_workspace() const noexcept { return {}; }\n\n";
  }
  h += "  [[nodiscard]] fuzzypid::Status infer(Scalar e, Scalar ec, Workspace& ws,\n"
       "                                       std::array<Scalar, 3>& delta) const noexcept {\n";
  h += "    namespace fz = fuzzypid::fuzzy;\n";
  if (!lock_previous) h += "    (void)ws;\n";
  h += "    delta = {};\n";
  h += "    Scalar in[" + num(m.num_inputs) + "] = {};\n";
  h += "    in[" + num(binding.input_of[0]) + "] = e;\n";
  h += "    in[" + num(binding.input_of[1]) + "] = ec;\n";
  h += "    if (!fuzzypid::detail::is_finite(e) || !fuzzypid::detail::is_finite(ec))\n"
       "      return fuzzypid::Status::NonFiniteInput;\n";
  h += body;
  h += "  }\n";
  if (m.num_points > 0) {
    h += "\n private:\n  // The (x, y) points of the Discrete terms.\n";
    h += "  static constexpr Scalar kPoints[] = {";
    for (std::size_t k = 0; k < 2 * m.num_points; ++k)
      h += std::string(k ? ", " : "") + lit(m.points[k]);
    h += "};\n";
  }
  h += "};\n\n";
  h += "// The shared, immutable supervisor the joints point to.\n"
       "template <class Scalar>\ninline constexpr Supervisor<Scalar> kSupervisor{};\n\n";
  return h;
}

}  // namespace fuzzypid::codegen
