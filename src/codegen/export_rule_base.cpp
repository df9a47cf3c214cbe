#include "export_rule_base.hpp"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <string>

#include "fuzzypid/supervisor/engine_supervisor.hpp"
#include "straight_line_supervisor.hpp"

namespace fuzzypid::codegen {

namespace {

using Model = fuzzy::EngineModel<double>;

std::string lit(double v) {
  return scalar_literal(v);
}

std::string num(std::size_t n) {
  return std::to_string(n);
}

template <class Enum>
std::string enum_lit(const char* type, Enum e) {
  return "static_cast<fuzzypid::fuzzy::" + std::string(type) + ">(" +
         std::to_string(static_cast<unsigned>(e)) + ")";
}

std::string b(bool v) {
  return v ? "true" : "false";
}

std::string term(const fuzzy::Term<double>& t) {
  return "{" + enum_lit("Shape", t.shape) + ", {" + lit(t.p[0]) + ", " + lit(t.p[1]) + ", " +
         lit(t.p[2]) + ", " + lit(t.p[3]) + "}, " + lit(t.height) + ", " + num(t.first) + ", " +
         num(t.count) + "}";
}

std::string hedges(const std::array<fuzzy::Hedge, fuzzy::kMaxHedges>& h) {
  std::string s = "{";
  for (std::size_t k = 0; k < h.size(); ++k)
    s += (k ? ", " : "") + enum_lit("Hedge", h[k]);
  return s + "}";
}

std::string comment_safe(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return s;
}

// A fuzzy::Name as a braced list of character literals (NUL-padded by the aggregate).
std::string name_literal(const fuzzy::Name& n) {
  std::string s = "{{";
  for (std::size_t k = 0; k < n.size() && n[k] != '\0'; ++k) {
    const auto c = static_cast<unsigned char>(n[k]);
    char buf[16];
    if (c >= 0x20 && c < 0x7f && c != '\'' && c != '\\')
      std::snprintf(buf, sizeof buf, "'%c', ", c);
    else
      std::snprintf(buf, sizeof buf, "'\\x%02x', ", c);
    s += buf;
  }
  return s + "}}";
}

std::size_t at_least_one(std::size_t n) {
  return n > 0 ? n : 1;
}

}  // namespace

std::string check_rule_base_float_range(const Model& m) {
  const auto bad = [](double v) {
    return std::isfinite(v) && std::fabs(v) > static_cast<double>(FLT_MAX);
  };
  const auto term_bad = [&](const fuzzy::Term<double>& t) {
    return bad(t.p[0]) || bad(t.p[1]) || bad(t.p[2]) || bad(t.p[3]) || bad(t.height);
  };
  const std::string tail = " is finite but not as a float (|x| <= 3.4e38)";
  for (std::size_t i = 0; i < m.num_inputs; ++i) {
    const auto& in = m.inputs[i];
    if (bad(in.min) || bad(in.max)) return "the rule file's input " + num(i + 1) + " range" + tail;
    for (std::size_t t = 0; t < in.num_terms; ++t)
      if (term_bad(in.terms[t]))
        return "the rule file's input " + num(i + 1) + " term " + num(t + 1) + tail;
  }
  for (std::size_t o = 0; o < m.num_outputs; ++o) {
    const auto& out = m.outputs[o];
    if (bad(out.min) || bad(out.max) || bad(out.default_value))
      return "the rule file's output " + num(o + 1) + " range or default" + tail;
    for (std::size_t t = 0; t < out.num_terms; ++t) {
      const auto& term = out.terms[t];
      bool any = term_bad(term.membership);
      for (const double c : term.coefficients)
        any = any || bad(c);
      if (any) return "the rule file's output " + num(o + 1) + " term " + num(t + 1) + tail;
    }
  }
  for (std::size_t k = 0; k < 2 * m.num_points; ++k)
    if (bad(m.points[k])) return "a Discrete point of the rule file" + tail;
  for (std::size_t k = 0; k < m.num_steps; ++k)
    if (bad(m.steps[k].value)) return "a number in a formula of the rule file" + tail;
  return {};
}

std::string export_rule_base(const Model& m, const std::string& rule_file) {
  std::size_t terms = 1;
  for (std::size_t i = 0; i < m.num_inputs; ++i)
    terms = std::max(terms, m.inputs[i].num_terms);
  for (std::size_t o = 0; o < m.num_outputs; ++o)
    terms = std::max(terms, m.outputs[o].num_terms);
  std::string h;
  h += "// The rule base of " + comment_safe(rule_file) + " (" + num(m.num_inputs) + " inputs, " +
       num(m.num_outputs) + " outputs, " + num(m.num_rules) + " rules in " + num(m.num_blocks) +
       " block(s)) for the fixed-capacity engine,\n// sized to the file: no parser, no heap.\n";
  h += "using RuleBaseCapacity = fuzzypid::fuzzy::EngineCapacity<" + num(m.num_inputs) + ", " +
       num(m.num_outputs) + ", " + num(terms) + ", " + num(at_least_one(m.num_rules)) + ", " +
       num(m.num_blocks) + ", " + num(at_least_one(m.num_tokens)) + ", " +
       num(at_least_one(m.num_conclusions)) + ", " + num(at_least_one(m.num_points)) +
       (m.num_steps > 0 ? ", " + num(m.num_steps) : std::string()) + ">;\n\n";
  h += "template <class Scalar>\nusing RuleBase = fuzzypid::fuzzy::EngineModel<Scalar, "
       "RuleBaseCapacity>;\n\n";
  h += "template <class Scalar>\nconstexpr RuleBase<Scalar> make_rule_base() noexcept {\n";
  h += "  RuleBase<Scalar> m{};\n";
  h += "  m.name = " + name_literal(m.name) + ";\n";
  h += "  m.num_inputs = " + num(m.num_inputs) + ";\n  m.num_outputs = " + num(m.num_outputs) +
       ";\n  m.num_rules = " + num(m.num_rules) + ";\n  m.num_blocks = " + num(m.num_blocks) +
       ";\n  m.num_tokens = " + num(m.num_tokens) +
       ";\n  m.num_conclusions = " + num(m.num_conclusions) +
       ";\n  m.num_points = " + num(m.num_points) + ";\n  m.chained = " + b(m.chained) +
       ";\n  m.power_hedges = " + b(m.power_hedges) + ";\n";
  if (m.num_steps > 0) h += "  m.num_steps = " + num(m.num_steps) + ";\n";
  for (std::size_t i = 0; i < m.num_inputs; ++i) {
    const auto& in = m.inputs[i];
    const std::string v = "  m.inputs[" + num(i) + "]";
    h += v + ".name = " + name_literal(in.name) + ";\n";
    h += v + ".min = " + lit(in.min) + ";\n" + v + ".max = " + lit(in.max) + ";\n";
    h += v + ".lock_range = " + b(in.lock_range) + ";\n";
    h += v + ".enabled = " + b(in.enabled) + ";\n";
    h += v + ".num_terms = " + num(in.num_terms) + ";\n";
    for (std::size_t t = 0; t < in.num_terms; ++t) {
      h += v + ".terms[" + num(t) + "] = " + term(in.terms[t]) + ";\n";
      h += v + ".term_names[" + num(t) + "] = " + name_literal(in.term_names[t]) + ";\n";
    }
  }
  for (std::size_t o = 0; o < m.num_outputs; ++o) {
    const auto& out = m.outputs[o];
    const std::string v = "  m.outputs[" + num(o) + "]";
    h += v + ".name = " + name_literal(out.name) + ";\n";
    h += v + ".min = " + lit(out.min) + ";\n" + v + ".max = " + lit(out.max) + ";\n";
    h += v + ".lock_range = " + b(out.lock_range) + ";\n";
    h += v + ".lock_previous = " + b(out.lock_previous) + ";\n";
    h += v + ".enabled = " + b(out.enabled) + ";\n";
    h += v + ".has_aggregation = " + b(out.has_aggregation) + ";\n";
    h += v + ".default_value = " + lit(out.default_value) + ";\n";
    h += v + ".defuzzifier = " + enum_lit("Defuzzifier", out.defuzzifier) + ";\n";
    h += v + ".resolution = " + std::to_string(out.resolution) + ";\n";
    h += v + ".exact_centroid = " + b(out.exact_centroid) + ";\n";
    h += v + ".aggregation = " + enum_lit("SNorm", out.aggregation) + ";\n";
    h += v + ".merge_equal_singletons = " + b(out.merge_equal_singletons) + ";\n";
    h += v + ".group_by_term = " + b(out.group_by_term) + ";\n";
    h += v + ".num_terms = " + num(out.num_terms) + ";\n";
    for (std::size_t t = 0; t < out.num_terms; ++t) {
      const auto& term_o = out.terms[t];
      const std::string w = v + ".terms[" + num(t) + "]";
      h += v + ".term_names[" + num(t) + "] = " + name_literal(out.term_names[t]) + ";\n";
      h += w + ".kind = " + enum_lit("OutputTermKind", term_o.kind) + ";\n";
      if (term_o.kind == fuzzy::OutputTermKind::Membership ||
          term_o.kind == fuzzy::OutputTermKind::Function)
        h += w + ".membership = " + term(term_o.membership) + ";\n";
      for (std::size_t c = 0; c < term_o.coefficients.size(); ++c)
        h += w + ".coefficients[" + num(c) + "] = " + lit(term_o.coefficients[c]) + ";\n";
    }
  }
  for (std::size_t k = 0; k < m.num_blocks; ++k) {
    const auto& bl = m.blocks[k];
    const std::string v = "  m.blocks[" + num(k) + "]";
    h += v + ".conjunction = " + enum_lit("TNorm", bl.conjunction) + ";\n";
    h += v + ".disjunction = " + enum_lit("SNorm", bl.disjunction) + ";\n";
    h += v + ".implication = " + enum_lit("TNorm", bl.implication) + ";\n";
    h += v + ".has_conjunction = " + b(bl.has_conjunction) + ";\n";
    h += v + ".has_disjunction = " + b(bl.has_disjunction) + ";\n";
    h += v + ".has_implication = " + b(bl.has_implication) + ";\n";
    h += v + ".activation = " + enum_lit("ActivationMethod", bl.activation) + ";\n";
    h += v + ".comparison = " + enum_lit("Comparison", bl.comparison) + ";\n";
    h += v + ".count = " + std::to_string(bl.count) + ";\n";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%a", bl.threshold);
    h += v + ".threshold = " + buf + ";\n";
  }
  // Rules: {first_token, num_tokens, first_conclusion, num_conclusions, block, weight}.
  for (std::size_t r = 0; r < m.num_rules; ++r) {
    const auto& rule = m.rules[r];
    h += "  m.rules[" + num(r) + "] = {" + num(rule.first_token) + ", " + num(rule.num_tokens) +
         ", " + num(rule.first_conclusion) + ", " + num(rule.num_conclusions) + ", " +
         num(rule.block) + ", " + lit(rule.weight) + "};\n";
  }
  // Tokens: {kind, input, term, num_hedges, hedges, power_tenths}.
  for (std::size_t k = 0; k < m.num_tokens; ++k) {
    const auto& t = m.tokens[k];
    h += "  m.tokens[" + num(k) + "] = {static_cast<fuzzypid::fuzzy::Token::Kind>(" +
         num(static_cast<unsigned>(t.kind)) + "), " + num(t.input) + ", " + num(t.term) + ", " +
         num(t.num_hedges) + ", " + hedges(t.hedges) + ", " + num(t.power_tenths) + "};\n";
  }
  // Conclusions: {output, term, num_hedges, hedges, power_tenths}.
  for (std::size_t k = 0; k < m.num_conclusions; ++k) {
    const auto& c = m.conclusions[k];
    h += "  m.conclusions[" + num(k) + "] = {" + num(c.output) + ", " + num(c.term) + ", " +
         num(c.num_hedges) + ", " + hedges(c.hedges) + ", " + num(c.power_tenths) + "};\n";
  }
  for (std::size_t k = 0; k < 2 * m.num_points; ++k)
    h += "  m.points[" + num(k) + "] = " + lit(m.points[k]) + ";\n";
  // Formula steps (Function terms): {op, input, value}.
  for (std::size_t k = 0; k < m.num_steps; ++k) {
    const auto& st = m.steps[k];
    h += "  m.steps[" + num(k) + "] = {static_cast<fuzzypid::fuzzy::FormulaOp>(" +
         num(static_cast<unsigned>(st.op)) + "), " + num(st.input) + ", " + lit(st.value) + "};\n";
  }
  h += "  return m;\n}\n\n";
  h += "// The rule base in flash (read-only data), shared by every joint.\n";
  h += "template <class Scalar>\ninline constexpr RuleBase<Scalar> kRuleBase = "
       "make_rule_base<Scalar>();\n\n";
  // `m` is a valid supervisor (export-header checked it), so every name is found once.
  SupervisorBinding binding;
  for (std::size_t k = 0; k < 2; ++k)
    binding.input_of[k] = static_cast<std::size_t>(supervisor::supervisor_detail::index_named(
        m.inputs, m.num_inputs, supervisor::kSupervisorInputNames[k]));
  for (std::size_t g = 0; g < 3; ++g)
    binding.output_of[g] = static_cast<std::size_t>(supervisor::supervisor_detail::index_named(
        m.outputs, m.num_outputs, supervisor::kSupervisorOutputNames[g]));
  const std::string refusal = straight_line_refusal(m);
  if (refusal.empty()) return h + straight_line_supervisor(m, binding);

  h += "// The supervisor FuzzyPid calls (the concept of fuzzypid/supervisor/supervisor.hpp): the "
       "rule\n"
       "// base at (e, ec) gives (dKp, dKi, dKd), as supervisor::EngineSupervisor with a fixed\n"
       "// workspace per joint. Interpreted, not straight-line code: " +
       comment_safe(refusal) + ".\n";
  std::string supervisor = R"(template <class Scalar>
class Supervisor {
 public:
  using Workspace = fuzzypid::fuzzy::EngineWorkspace<Scalar, RuleBaseCapacity>;

  Workspace make_workspace() const noexcept { return {}; }

  [[nodiscard]] fuzzypid::Status infer(Scalar e, Scalar ec, Workspace& ws,
                                       std::array<Scalar, 3>& delta) const noexcept {
    Scalar in[2] = {};
    in[kInputOf[0]] = e;
    in[kInputOf[1]] = ec;
    Scalar out[3] = {};
    const fuzzypid::Status s = fuzzypid::fuzzy::evaluate(kRuleBase<Scalar>, ws.view(), in, out);
    for (std::size_t g = 0; g < 3; ++g)
      delta[g] = out[kOutputOf[g]];
    return s;
  }

 private:
  // The rule base's index of e, ec and of dKp, dKi, dKd (bound by name at export).
  static constexpr std::size_t kInputOf[2] = {@IN@};
  static constexpr std::size_t kOutputOf[3] = {@OUT@};
};

// The shared, immutable supervisor the joints point to.
template <class Scalar>
inline constexpr Supervisor<Scalar> kSupervisor{};

)";
  const std::string in = num(binding.input_of[0]) + ", " + num(binding.input_of[1]);
  const std::string out = num(binding.output_of[0]) + ", " + num(binding.output_of[1]) + ", " +
                          num(binding.output_of[2]);
  supervisor.replace(supervisor.find("@IN@"), 4, in);
  supervisor.replace(supervisor.find("@OUT@"), 5, out);
  h += supervisor;
  return h;
}

std::string scalar_literal(double v) {
  if (std::isnan(v)) return "std::numeric_limits<Scalar>::quiet_NaN()";
  if (std::isinf(v))
    return v > 0 ? "std::numeric_limits<Scalar>::infinity()"
                 : "-std::numeric_limits<Scalar>::infinity()";
  char buf[64];
  std::snprintf(buf, sizeof buf, "Scalar(%a)", v);
  return buf;
}

}  // namespace fuzzypid::codegen
