// Evaluation of a fuzzy inference engine model (fuzzy/engine_model.hpp) into a workspace
// (fuzzy/engine_workspace.hpp): the form a rule base loaded from a MATLAB .fis, fuzzylite .fll or
// IEC 61131-7 .fcl file takes (see fuzzypid/rulefile/rule_file.hpp and docs/rule_files.md).
//
// Per evaluation (fuzzylite 6's semantics, its tolerance macheps set to 0; Engine::process):
//   mu_it          = term t of input i at x_i (x_i clamped to the range if lock_range)
//   proposition    = hedges applied right to left to mu_it ("x is very not A" = very(not(mu_A)));
//                    a proposition whose last hedge is `any` is 1 before the other hedges.
//                    "y is A" on an OUTPUT y (chained systems) reads the degree of A in y's fuzzy
//                    output so far: the output's aggregation folded from 0 over the activations
//                    of A by the rules triggered before this one (the sum when the output has no
//                    aggregation), fuzzylite's Aggregated::activationDegree
//   blocks         = in file order; within a block, General, Threshold, First and Last compute
//                    each rule's strength and trigger it before the next rule (Last from the
//                    block's end), so later rules see earlier rules' conclusions; Proportional,
//                    Highest and Lowest compute all of the block's strengths first, then trigger
//                    the rules they select (fuzzylite's Activation::activate)
//   antecedent     = the rule's expression of propositions joined by `and` (its block's
//                    conjunction) and `or` (its block's disjunction); `and` binds tighter, as in
//                    fuzzylite, and parentheses group
//   rule strength  = weight * antecedent; which rules fire is the block's activation method
//                    (General: every rule with strength > 0, in rule order; see RuleBlock)
//   conclusions    = in rule order, each conclusion's hedges are applied (right to left) to the
//                    running degree, which is then the degree of that conclusion (fuzzylite's
//                    Consequent::modify); a conclusion with Octave's power hedge .dd (a .fis)
//                    has the degree w^(1/(dd/10)), then its hedges, and leaves the running
//                    degree alone (eval_rules_sugeno). A proposition's power hedge raises the
//                    term's degree to dd/10 before the other hedges (evalmf)
//   Mamdani output: activations (term, degree, the block's implication), aggregated by the
//     output's s-norm (folded from 0 in rule order), then centroid (sampled or exact), bisector,
//     mean/smallest/largest of maximum. With Maximum aggregation and a Minimum/Product implication
//     shared by all blocks, one activation per term holds the largest degree (exact, as both are
//     monotone).
//   Sugeno output (constant/linear terms): z_r = c or sum_i c_i x_i + c_0 per conclusion;
//     weighted average sum(w_r z_r) / sum(w_r) or weighted sum sum(w_r z_r). With
//     merge_equal_singletons (Octave's aggregate_output_sugeno), conclusions of equal z are one
//     singleton whose weight is the output's aggregation of theirs.
//   Tsukamoto output (weighted defuzzifier over Ramp/Sigmoid/SShape/ZShape/Concave/Arc terms):
//     z_r is the abscissa where the term reaches w_r (fuzzylite 8's exact inverses), then as
//     Sugeno.
//   group_by_term (fuzzylite 8, set by the .fll/.fcl readers): a weighted output's activations
//     of each term fold into one degree w_t by its aggregation (the sum without one), and the
//     sums run over terms: sum(w_t z_t(w_t)) (/ sum(w_t)), z_t as above at w_t.
//   Function terms (fuzzy/formula.hpp): an input's term is its formula at x = x_i and the inputs'
//     values (after locking); a Takagi-Sugeno output's term gives z_r = its formula at the inputs'
//     values. A formula value that is not finite (a domain error: sqrt(-1), 1 / 0) is
//     Status::NumericOverflow: an input term's makes every output 0, an output term's makes that
//     output 0.
// The model is plain data; evaluation writes only into a separate workspace, is noexcept and
// allocates nothing. An output no rule concluded on takes its previous value when lock_previous
// and a previous evaluation with this workspace gave a finite value (kept in the workspace, so
// the model stays immutable), else its default value, or 0 with Status::NoRuleFired when the
// default is NaN (fuzzylite's "default: nan"); an output whose defuzzification has no area is 0
// with NoRuleFired too (fuzzylite gives NaN).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "fuzzypid/fuzzy/defuzzify.hpp"
#include "fuzzypid/fuzzy/engine_model.hpp"
#include "fuzzypid/fuzzy/engine_model_validation.hpp"
#include "fuzzypid/fuzzy/engine_workspace.hpp"
#include "fuzzypid/fuzzy/formula.hpp"
#include "fuzzypid/fuzzy/membership.hpp"
#include "fuzzypid/fuzzy/operators.hpp"
#include "fuzzypid/scalar.hpp"
#include "fuzzypid/status.hpp"

namespace fuzzypid::fuzzy {

namespace engine_detail {

template <class Scalar>
Scalar hedge_right_to_left(const std::array<Hedge, kMaxHedges>& hedges, std::size_t n,
                           Scalar x) noexcept {
  for (std::size_t k = n; k-- > 0;)
    x = apply(hedges[k], x);
  return x;
}

// "variable is [hedges] term": the hedges right to left on the term's degree (an input's
// membership, or an output's degree so far); 1 when the last hedge is `any` (fuzzylite's
// Antecedent::activationDegree).
template <bool Power, class Scalar>
Scalar proposition(const WorkspaceView<Scalar>& ws, const Token& tok) noexcept {
  const std::size_t n = tok.num_hedges;
  if (n > 0 && tok.hedges[n - 1] == Hedge::Any)
    return hedge_right_to_left(tok.hedges, n - 1, Scalar(1));
  const Scalar* degrees = tok.kind == Token::Kind::OutputProposition ? ws.degree : ws.membership;
  Scalar mu = degrees[tok.input * ws.stride + tok.term];
  // Octave's evalmf: mu .^ (dd / 10), then `not`.
  if constexpr (Power)
    if (tok.power_tenths != 0)
      mu = std::pow(mu, static_cast<Scalar>(tok.power_tenths) / Scalar(10));
  return hedge_right_to_left(tok.hedges, n, mu);
}

// The degree of conclusion c of a rule of firing strength w. `running` is the rule's running
// degree (w before its first conclusion): fuzzylite's hedges modify it for this conclusion and
// the later ones (Consequent::modify); Octave's power hedge .dd gives w^(1 / (dd / 10)), then
// `not`, for this conclusion only (eval_rules_sugeno).
template <bool Power, class Scalar>
Scalar conclusion_degree(const Conclusion& c, Scalar w, Scalar& running) noexcept {
  if constexpr (Power) {
    if (c.power_tenths != 0) {
      const Scalar exponent = Scalar(1) / (static_cast<Scalar>(c.power_tenths) / Scalar(10));
      return hedge_right_to_left(c.hedges, c.num_hedges, std::pow(w, exponent));
    }
  } else {
    (void)w;
  }
  return running = hedge_right_to_left(c.hedges, c.num_hedges, running);
}

// z of a constant or linear term: c, or sum_i c_i x_i + c_0 over the inputs after locking.
template <class Scalar, class Cap>
Scalar sugeno_value(const OutputTerm<Scalar, Cap>& term, const Scalar* input,
                    std::size_t num_inputs) noexcept {
  if (term.kind != OutputTermKind::Linear) return term.coefficients[0];
  Scalar z = Scalar(0);
  for (std::size_t i = 0; i < num_inputs; ++i)
    z += term.coefficients[i] * input[i];
  return z + term.coefficients[num_inputs];
}

// Weight times the antecedent of rule r (postfix evaluation on ws.stack). `disabled`: the model
// has disabled variables, whose propositions are 0.
template <bool Power, class Scalar, class Model>
Scalar rule_strength(const Model& model, const WorkspaceView<Scalar>& ws, std::size_t r,
                     bool disabled) noexcept {
  const Rule<Scalar>& rule = model.rules[r];
  const RuleBlock& block = model.blocks[rule.block];
  std::size_t sp = 0;
  for (std::size_t k = 0; k < rule.num_tokens; ++k) {
    const Token& tok = model.tokens[rule.first_token + k];
    if (tok.kind == Token::Kind::And || tok.kind == Token::Kind::Or) {
      const Scalar b = ws.stack[--sp];
      const Scalar a = ws.stack[sp - 1];
      ws.stack[sp - 1] = tok.kind == Token::Kind::And ? apply(block.conjunction, a, b)
                                                      : apply(block.disjunction, a, b);
    } else {
      const bool enabled = !disabled || (tok.kind == Token::Kind::OutputProposition
                                             ? model.outputs[tok.input].enabled
                                             : model.inputs[tok.input].enabled);
      ws.stack[sp++] = enabled ? proposition<Power>(ws, tok) : Scalar(0);
    }
  }
  return rule.weight * ws.stack[0];
}

// Adds rule r's conclusions to the outputs' term degrees that chained antecedents read
// (fuzzylite's Consequent::modify into Aggregated, then activationDegree).
template <bool Power, class Scalar, class Model>
void trigger(const Model& model, const WorkspaceView<Scalar>& ws, std::size_t r) noexcept {
  const Rule<Scalar>& rule = model.rules[r];
  Scalar running = ws.strength[r];
  for (std::size_t k = 0; k < rule.num_conclusions; ++k) {
    const Conclusion& c = model.conclusions[rule.first_conclusion + k];
    const auto& out = model.outputs[c.output];
    if (!out.enabled) continue;
    const Scalar degree = conclusion_degree<Power>(c, ws.strength[r], running);
    Scalar& d = ws.degree[c.output * ws.stride + c.term];
    d = out.has_aggregation ? apply(out.aggregation, d, degree) : d + degree;
  }
}

// The crisp value z with mu(z) = w of a monotonic term of height h (fuzzylite 8's
// Term::tsukamoto; fuzzylite 6's inverses miss mu(z) = w for Concave, SShape, ZShape and a height
// other than 1 -- docs/rule_files.md). For 0 < w <= h:
//   Ramp(s, e)       z = s + (e - s) w / h                                 (z in [s, e])
//   Sigmoid(i, k)    z = i + ln(h / w - 1) / -k
//   SShape(s, e)     z = s + (e - s) sqrt(w / 2h)        if w <= h / 2      (z in [s, e])
//                    z = e - (e - s) sqrt((h - w) / 2h)  otherwise
//   ZShape(s, e)     z = e - (e - s) sqrt(w / 2h)        if w <= h / 2      (z in [s, e])
//                    z = s + (e - s) sqrt((h - w) / 2h)  otherwise
//   Concave(i, e)    z = h (i - e) / w + 2e - i                            (z = e at w = h)
//   Arc(s, e)        z = c -+ sqrt(r^2 - (w r / h)^2), r = e - s, c = s + r, - when s < e
//                                                                          (z in [s, e])
// A degree above the term's height (no z reaches it) is taken as h: the point where the term
// reaches its height (fuzzylite 8 extrapolates Ramp and Concave there and gives NaN for the
// others). A sigmoid reaches h only at infinity: at w >= h (and at w <= 0, where it reaches 0)
// z is the end of the output range [min, max] the sigmoid tends to, a finite value where
// fuzzylite 8 gives +-inf.
template <class Scalar>
Scalar tsukamoto(const Term<Scalar>& t, Scalar w, Scalar min, Scalar max,
                 const Scalar* points) noexcept {
  const auto& p = t.p;
  const Scalar h = t.height;
  if (w > h) w = h;
  // Rounding may step an ulp past the term's stretch: keep z on it.
  const auto within = [&](Scalar z) {
    return detail::clamp(z, detail::min(p[0], p[1]), detail::max(p[0], p[1]));
  };
  switch (t.shape) {
    case Shape::Ramp:
      return within(p[0] + (p[1] - p[0]) * w / h);
    case Shape::Sigmoid:
      if (w >= h) return p[1] >= Scalar(0) ? max : min;
      if (w <= Scalar(0)) return p[1] >= Scalar(0) ? min : max;
      return p[0] + std::log(h / w - Scalar(1)) / -p[1];
    case Shape::SShape:
      if (w <= h / Scalar(2)) return within(p[0] + (p[1] - p[0]) * std::sqrt(w / (Scalar(2) * h)));
      return within(p[1] - (p[1] - p[0]) * std::sqrt((h - w) / (Scalar(2) * h)));
    case Shape::ZShape:
      if (w <= h / Scalar(2)) return within(p[1] - (p[1] - p[0]) * std::sqrt(w / (Scalar(2) * h)));
      return within(p[0] + (p[1] - p[0]) * std::sqrt((h - w) / (Scalar(2) * h)));
    case Shape::Concave: {
      const Scalar z = h * (p[0] - p[1]) / w + Scalar(2) * p[1] - p[0];
      return p[0] <= p[1] ? detail::min(z, p[1]) : detail::max(z, p[1]);
    }
    case Shape::Arc: {
      const Scalar r = p[1] - p[0];
      const Scalar c = p[0] + r;
      const Scalar a = w * r / h;
      const Scalar d = std::sqrt(detail::max(Scalar(0), r * r - a * a));
      return within(p[0] < p[1] ? c - d : c + d);
    }
    default:
      return t(w, points);
  }
}

// The memberships of the enabled inputs' Function terms (out of line and cold: the paths of models
// without formulas stay as they are). False when one is not finite.
template <class Scalar, class Cap>
[[gnu::cold]] [[gnu::noinline]] bool formula_memberships(const EngineModel<Scalar, Cap>& model,
                                                         const WorkspaceView<Scalar>& ws) noexcept {
  for (std::size_t i = 0; i < model.num_inputs; ++i) {
    const auto& in = model.inputs[i];
    if (!in.enabled) continue;
    for (std::size_t t = 0; t < in.num_terms; ++t) {
      const Term<Scalar>& term = in.terms[t];
      if (term.shape != Shape::Function) continue;
      const Scalar mu =
          evaluate_formula(model.steps.data() + term.first, term.count, ws.input[i], ws.input);
      if (!detail::is_finite(mu)) return false;
      ws.membership[i * ws.stride + t] = mu;
    }
  }
  return true;
}

// z of a Takagi-Sugeno output's Function term at the inputs' values; NaN when not finite (the
// output is then NaN, which evaluate_with reports as NumericOverflow).
template <class Scalar, class Cap>
Scalar formula_value(const EngineModel<Scalar, Cap>& model, const Term<Scalar>& term,
                     const Scalar* input) noexcept {
  const Scalar nan = std::numeric_limits<Scalar>::quiet_NaN();
  const Scalar z = evaluate_formula(model.steps.data() + term.first, term.count, nan, input);
  return detail::is_finite(z) ? z : nan;
}

// formula_value of each Function term of `out` into level[t] (out of line and cold, and before
// the conclusions' loop, which then only reads them).
template <class Scalar, class Cap>
[[gnu::cold]] [[gnu::noinline]] void formula_values(const EngineModel<Scalar, Cap>& model,
                                                    const OutputSpec<Scalar, Cap>& out,
                                                    const Scalar* input, Scalar* level) noexcept {
  for (std::size_t t = 0; t < out.num_terms; ++t)
    if (out.terms[t].kind == OutputTermKind::Function)
      level[t] = formula_value(model, out.terms[t].membership, input);
}

// z of a weighted output's term t at the degree w: Tsukamoto's inverse, a formula (NaN where not
// finite) or a constant/linear value.
template <class Scalar, class Cap>
Scalar weighted_value(const EngineModel<Scalar, Cap>& model, const OutputSpec<Scalar, Cap>& out,
                      std::size_t t, Scalar w, const Scalar* input, const Scalar* points) noexcept {
  const OutputTerm<Scalar, Cap>& term = out.terms[t];
  switch (term.kind) {
    case OutputTermKind::Membership:
      return tsukamoto(term.membership, w, out.min, out.max, points);
    case OutputTermKind::Function:
      return formula_value(model, term.membership, input);
    default:
      return sugeno_value(term, input, model.num_inputs);
  }
}

template <class Scalar>
bool compare(Comparison c, Scalar a, Scalar b) noexcept {
  switch (c) {
    case Comparison::LessThan:
      return a < b;
    case Comparison::LessThanOrEqualTo:
      return a <= b;
    case Comparison::EqualTo:
      return a == b;
    case Comparison::NotEqualTo:
      return a != b;
    case Comparison::GreaterThanOrEqualTo:
      return a >= b;
    case Comparison::GreaterThan:
      return a > b;
  }
  return false;
}

// Evaluates block b's rules and appends those that fire to ws.order[n ..) in firing order; returns
// the new number of fired rules. The order of evaluation is fuzzylite's Activation::activate, which
// matters when antecedents test outputs: General, Threshold, First and Last evaluate and trigger
// rule by rule (Last from the block's last rule up), so a rule sees the conclusions of the rules
// triggered before it; Proportional, Highest and Lowest evaluate all of the block's rules first.
template <bool Power, class Scalar, class Model>
std::size_t activate_block(const Model& model, const WorkspaceView<Scalar>& ws, std::size_t b,
                           std::size_t n, bool disabled) noexcept {
  const Scalar zero = Scalar(0);
  const RuleBlock& block = model.blocks[b];
  const auto in_block = [&](std::size_t r) { return model.rules[r].block == b; };
  const Scalar threshold = static_cast<Scalar>(block.threshold);
  const auto fire = [&](std::size_t r) {
    ws.order[n++] = static_cast<std::uint32_t>(r);
    if (model.chained) trigger<Power>(model, ws, r);
  };
  switch (block.activation) {
    case ActivationMethod::General:
    case ActivationMethod::Threshold:
    case ActivationMethod::First:
    case ActivationMethod::Last: {
      const bool last = block.activation == ActivationMethod::Last;
      std::uint32_t taken = 0;
      for (std::size_t k = 0; k < model.num_rules; ++k) {
        const std::size_t r = last ? model.num_rules - 1 - k : k;
        if (!in_block(r)) continue;
        const Scalar w = ws.strength[r] = rule_strength<Power>(model, ws, r, disabled);
        bool fires = w > zero;
        if (block.activation == ActivationMethod::Threshold)
          fires = fires && compare(block.comparison, w, threshold);
        else if (block.activation != ActivationMethod::General)
          fires = fires && taken < block.count && w >= threshold;
        if (fires) {
          fire(r);
          ++taken;
        }
      }
      return n;
    }
    case ActivationMethod::Proportional: {
      Scalar sum = zero;
      for (std::size_t r = 0; r < model.num_rules; ++r)
        if (in_block(r)) sum += ws.strength[r] = rule_strength<Power>(model, ws, r, disabled);
      for (std::size_t r = 0; r < model.num_rules; ++r) {
        if (!in_block(r)) continue;
        ws.strength[r] = ws.strength[r] / sum;
        if (ws.strength[r] > zero) fire(r);
      }
      return n;
    }
    case ActivationMethod::Highest:
    case ActivationMethod::Lowest: {
      // The same heap operations as fuzzylite's std::priority_queue, so ties pop in its order.
      const bool highest = block.activation == ActivationMethod::Highest;
      const auto before = [&](std::uint32_t a, std::uint32_t c) {
        return highest ? ws.strength[a] < ws.strength[c] : ws.strength[a] > ws.strength[c];
      };
      std::size_t size = 0;
      for (std::size_t r = 0; r < model.num_rules; ++r) {
        if (!in_block(r)) continue;
        ws.strength[r] = rule_strength<Power>(model, ws, r, disabled);
        if (!(ws.strength[r] > zero)) continue;
        ws.heap[size++] = static_cast<std::uint32_t>(r);
        std::push_heap(ws.heap, ws.heap + size, before);
      }
      for (std::uint32_t taken = 0; size > 0 && taken < block.count; ++taken) {
        fire(ws.heap[0]);
        std::pop_heap(ws.heap, ws.heap + size, before);
        --size;
      }
      return n;
    }
  }
  return n;
}

// fuzzy::evaluate; Power: the model holds Octave's power hedges, whose std::pow calls the other
// instance leaves out of its loops (a call there costs the common case a quarter of its speed on
// a Cortex-M4F, measured by embedded.rule_file_cortex_m4_qemu).
template <bool Power, class Scalar, class Cap>
Status evaluate_with(const EngineModel<Scalar, Cap>& model, const WorkspaceView<Scalar>& ws,
                     const Scalar* inputs, Scalar* outputs) noexcept {
  for (std::size_t o = 0; o < model.num_outputs; ++o)
    outputs[o] = Scalar(0);
  for (std::size_t i = 0; i < model.num_inputs; ++i)
    if (!detail::is_finite(inputs[i])) return Status::NonFiniteInput;

  // No pool when no term is Discrete (validate: a Discrete term lies within num_points).
  const Scalar* points = model.num_points > 0 ? model.points.data() : nullptr;
  for (std::size_t i = 0; i < model.num_inputs; ++i) {
    const auto& in = model.inputs[i];
    const Scalar x = in.lock_range ? detail::clamp(inputs[i], in.min, in.max) : inputs[i];
    ws.input[i] = x;  // Linear terms read disabled inputs too, as fuzzylite
    if (!in.enabled) continue;
    for (std::size_t t = 0; t < in.num_terms; ++t)
      ws.membership[i * ws.stride + t] = in.terms[t](x, points);
  }
  if (model.num_steps > 0 && !engine_detail::formula_memberships(model, ws))
    return Status::NumericOverflow;  // the outputs are 0, written above

  const bool disabled = model.has_disabled_variables();
  if (model.chained)
    for (std::size_t k = 0; k < model.num_outputs * ws.stride; ++k)
      ws.degree[k] = Scalar(0);
  std::size_t fired_rules = 0;
  for (std::size_t b = 0; b < model.num_blocks; ++b)
    fired_rules = engine_detail::activate_block<Power>(model, ws, b, fired_rules, disabled);

  const bool merged = model.merges_activations();
  // Some term is a Function (a loop invariant; a constant for a constexpr model without one).
  const bool formulas = model.num_steps > 0;
  Status status = Status::Ok;
  for (std::size_t o = 0; o < model.num_outputs; ++o) {
    const OutputSpec<Scalar, Cap>& out = model.outputs[o];
    if (!out.enabled) continue;  // 0, written above
    const bool sugeno = is_sugeno(out.defuzzifier);
    const bool merge = !sugeno && merged && out.aggregation == SNorm::Maximum;
    const bool singletons = sugeno && out.merge_equal_singletons;
    const bool grouped = out.group_by_term;  // validate(): weighted, never with singletons
    Scalar y = std::numeric_limits<Scalar>::quiet_NaN();
    bool fired = false;
    Scalar sum = Scalar(0);
    Scalar weights = Scalar(0);
    std::size_t n = 0;
    if (merge || singletons)
      for (std::size_t t = 0; t < out.num_terms; ++t)
        ws.level[t] = Scalar(0);
    // NaN: no activation of the term yet (a degree is never NaN: the inputs are finite).
    if (grouped)
      for (std::size_t t = 0; t < out.num_terms; ++t)
        ws.level[t] = std::numeric_limits<Scalar>::quiet_NaN();
    // Other Takagi-Sugeno outputs neither merge nor take singletons: level holds their formulas'
    // z.
    else if (formulas && sugeno)
      engine_detail::formula_values(model, out, ws.input, ws.level);
    for (std::size_t f = 0; f < fired_rules; ++f) {
      const std::size_t r = ws.order[f];
      const Rule<Scalar>& rule = model.rules[r];
      Scalar running = ws.strength[r];
      for (std::size_t k = 0; k < rule.num_conclusions; ++k) {
        const Conclusion& c = model.conclusions[rule.first_conclusion + k];
        if (disabled && !model.outputs[c.output].enabled) continue;
        const Scalar degree = engine_detail::conclusion_degree<Power>(c, ws.strength[r], running);
        if (c.output != o) continue;
        fired = true;
        const OutputTerm<Scalar, Cap>& term = out.terms[c.term];
        if (grouped) {
          // fuzzylite 8's Aggregated::grouped_terms: the first activation of a term is its degree,
          // later ones fold in with the aggregation (the sum when there is none).
          Scalar& w = ws.level[c.term];
          w = w != w
                  ? degree
                  : apply(out.has_aggregation ? out.aggregation : SNorm::UnboundedSum, w, degree);
        } else if (singletons) {
          // A term's value z is the same in every rule: its degrees aggregate first (folded
          // from 0, the identity of every s-norm), equal values of other terms below.
          ws.level[c.term] = apply(out.aggregation, ws.level[c.term], degree);
        } else if (sugeno) {
          // Membership terms of a sized model hold no coefficients.
          const Scalar z =
              term.kind == OutputTermKind::Membership
                  ? engine_detail::tsukamoto(term.membership, degree, out.min, out.max, points)
              : formulas && term.kind == OutputTermKind::Function
                  ? ws.level[c.term]
                  : engine_detail::sugeno_value(term, ws.input, model.num_inputs);
          sum += degree * z;
          weights += degree;
        } else if (merge) {
          ws.level[c.term] = detail::max(ws.level[c.term], degree);
        } else {
          ws.activations[n++] = {&term.membership, degree, model.blocks[rule.block].implication};
        }
      }
    }
    if (fired && grouped) {
      for (std::size_t t = 0; t < out.num_terms; ++t) {
        const Scalar w = ws.level[t];
        if (w != w) continue;  // not concluded
        sum += w * engine_detail::weighted_value(model, out, t, w, ws.input, points);
        weights += w;
      }
      y = out.defuzzifier == Defuzzifier::WeightedAverage ? sum / weights : sum;
    } else if (fired && singletons) {
      // Octave's aggregate_output_sugeno: the singletons of equal z are one, of the aggregation
      // of their degrees (a term's value is recomputed rather than stored: no scratch beyond
      // one level per term).
      for (std::size_t t = 0; t < out.num_terms; ++t) {
        if (!(ws.level[t] > Scalar(0))) continue;
        const Scalar z = engine_detail::sugeno_value(out.terms[t], ws.input, model.num_inputs);
        for (std::size_t u = 0; u < t; ++u)
          if (ws.level[u] > Scalar(0) &&
              engine_detail::sugeno_value(out.terms[u], ws.input, model.num_inputs) == z) {
            ws.level[u] = apply(out.aggregation, ws.level[u], ws.level[t]);
            ws.level[t] = Scalar(0);
            break;
          }
      }
      for (std::size_t t = 0; t < out.num_terms; ++t)
        if (ws.level[t] > Scalar(0)) {
          sum +=
              ws.level[t] * engine_detail::sugeno_value(out.terms[t], ws.input, model.num_inputs);
          weights += ws.level[t];
        }
      y = out.defuzzifier == Defuzzifier::WeightedAverage ? sum / weights : sum;
    } else if (fired && sugeno) {
      y = out.defuzzifier == Defuzzifier::WeightedAverage ? sum / weights : sum;
    } else if (fired) {
      if (merge)
        for (std::size_t t = 0; t < out.num_terms; ++t)
          if (ws.level[t] > Scalar(0))
            ws.activations[n++] = {&out.terms[t].membership, ws.level[t],
                                   model.blocks[0].implication};
      const AggregatedSet<Scalar> set{ws.activations, n, out.aggregation, points};
      switch (out.defuzzifier) {
        case Defuzzifier::Centroid:
          y = out.exact_centroid ? centroid_exact(set, out.min, out.max, ws.breakpoints, ws.lines,
                                                  ws.crossings, ws.exact)
                                 : centroid_sampled(set, out.min, out.max, out.resolution);
          break;
        case Defuzzifier::Bisector:
          y = bisector_sampled(set, out.min, out.max, out.resolution);
          break;
        case Defuzzifier::MeanOfMaximum:
          y = of_maximum_sampled(MaximumKind::Mean, set, out.min, out.max, out.resolution);
          break;
        case Defuzzifier::SmallestOfMaximum:
          y = of_maximum_sampled(MaximumKind::Smallest, set, out.min, out.max, out.resolution);
          break;
        case Defuzzifier::LargestOfMaximum:
          y = of_maximum_sampled(MaximumKind::Largest, set, out.min, out.max, out.resolution);
          break;
        default:
          break;
      }
    }
    // fuzzylite's OutputVariable::defuzzify: the previous value only replaces an empty output.
    if (!fired)
      y = out.lock_previous && ws.previous[o] == ws.previous[o] ? ws.previous[o]
                                                                : out.default_value;
    if (y == y && out.lock_range) y = detail::clamp(y, out.min, out.max);
    if (detail::is_finite(y)) ws.previous[o] = y;
    if (y != y) {
      y = Scalar(0);
      // A fired Takagi-Sugeno output is NaN only where a formula was not finite (formula_value).
      status = worst(status,
                     fired && sugeno && formulas ? Status::NumericOverflow : Status::NoRuleFired);
    }
    outputs[o] = y;
  }
  return status;
}

}  // namespace engine_detail

// Evaluates `model` at inputs[0 .. num_inputs) into outputs[0 .. num_outputs). The model must
// have passed validate() and `ws` must fit it. Returns NonFiniteInput (outputs 0) for a NaN/inf
// input, NumericOverflow when a Function term's formula was not finite (see above), NoRuleFired
// when some output fell back to 0 because no rule fired for it, else Ok.
template <class Scalar, class Cap>
Status evaluate(const EngineModel<Scalar, Cap>& model, const WorkspaceView<Scalar>& ws,
                const Scalar* inputs, Scalar* outputs) noexcept {
  return model.power_hedges ? engine_detail::evaluate_with<true>(model, ws, inputs, outputs)
                            : engine_detail::evaluate_with<false>(model, ws, inputs, outputs);
}

// A model with its own workspace. For a fixed capacity the workspace is fixed too and nothing
// allocates (large for FixedCapacity, docs/rule_files.md: create it once, e.g. on the heap at
// start-up); for a sized capacity (DefaultCapacity) set_model copies the model and sizes the
// workspace to it, which allocates, while evaluate() does not.
template <class Scalar, class Cap = DefaultCapacity>
class Engine {
 public:
  using Model = EngineModel<Scalar, Cap>;
  using Workspace =
      std::conditional_t<Cap::sized, DynamicWorkspace<Scalar>, EngineWorkspace<Scalar, Cap>>;

  Engine() noexcept = default;
  // An invalid model leaves the engine unconfigured: evaluate() returns InvalidConfig.
  explicit Engine(const Model& model) noexcept(!Cap::sized) { (void)set_model(model); }

  // Also forgets the previous outputs (lock_previous).
  ModelError set_model(const Model& model) noexcept(!Cap::sized) {
    const ModelError error = validate(model);
    if (!error) model_ = model;
    if constexpr (Cap::sized)
      ws_ = error ? Workspace() : Workspace(model_);
    else
      ws_.previous = nan_array<Scalar, Cap::outputs>();
    configured_ = !error;
    return error;
  }

  // Writes num_outputs() values; see fuzzy::evaluate.
  Status evaluate(const Scalar* inputs, Scalar* outputs) noexcept {
    if (!configured_) return Status::InvalidConfig;
    return fuzzy::evaluate(model_, ws_.view(), inputs, outputs);
  }

  const Model& model() const noexcept { return model_; }
  std::size_t num_inputs() const noexcept { return model_.num_inputs; }
  std::size_t num_outputs() const noexcept { return model_.num_outputs; }
  // Firing strength of rule r in the last evaluation (weight included).
  Scalar rule_strength(std::size_t r) const noexcept { return ws_.strength[r]; }
  const Workspace& workspace() const noexcept { return ws_; }

 private:
  Model model_{};
  Workspace ws_{};
  bool configured_ = false;
};

}  // namespace fuzzypid::fuzzy
