// Validation of an engine model (fuzzy/engine_model.hpp): everything evaluation (fuzzy/engine.hpp)
// relies on, checked once at set-up. The rule-file readers check the same things with line numbers
// first and call validate() last; Engine::set_model refuses a model it rejects.
#pragma once

#include <cstddef>
#include <cstdint>

#include "fuzzypid/fuzzy/engine_model.hpp"
#include "fuzzypid/scalar.hpp"

namespace fuzzypid::fuzzy {

// Why a model failed validation: what is wrong, and which input, output or rule (index) it
// concerns.
struct ModelError {
  enum class Where : std::uint8_t { Model, Input, Output, Rule };
  const char* message = nullptr;  // nullptr when valid
  std::size_t index = 0;
  Where where = Where::Model;
  explicit operator bool() const noexcept { return message != nullptr; }
};

// The first thing wrong with `m`, or no error (message nullptr). Set-up, not the tick: it walks
// every term, rule and formula of the model.
template <class Scalar, class Cap>
[[nodiscard]] ModelError validate(const EngineModel<Scalar, Cap>& m) noexcept {
  if (m.num_inputs < 1 || m.num_inputs > Cap::inputs)
    return {"number of inputs out of capacity", 0};
  if (m.num_outputs < 1 || m.num_outputs > Cap::outputs)
    return {"number of outputs out of capacity", 0};
  if (m.num_rules > Cap::rules) return {"more rules than the capacity", 0};
  if (m.num_blocks < 1 || m.num_blocks > Cap::blocks)
    return {"number of rule blocks out of capacity", 0};
  if (m.num_tokens > Cap::tokens || m.num_conclusions > Cap::conclusions ||
      m.num_points > Cap::points || m.num_steps > Cap::steps)
    return {"rule, point or formula storage out of capacity", 0};
  if (!m.storage_holds_counts()) return {"storage smaller than the model's counts", 0};
  const auto range_ok = [](Scalar lo, Scalar hi) {
    return detail::is_finite(lo) && detail::is_finite(hi) && lo < hi;
  };
  // A formula reads x (input terms) and the inputs' values, within its own steps.
  const auto formula_ok = [&](const Term<Scalar>& t, bool x_allowed) {
    return t.shape == Shape::Function && t.count >= 1 &&
           static_cast<std::size_t>(t.first) + t.count <= m.num_steps &&
           formula_depth(m.steps.data() + t.first, t.count, m.num_inputs, x_allowed) > 0;
  };
  const auto term_ok = [&](const Term<Scalar>& t) {
    if (!t.valid()) return false;
    if (t.shape == Shape::Function) return formula_ok(t, true);
    if (t.shape != Shape::Discrete) return true;
    if (static_cast<std::size_t>(t.first) + t.count > m.num_points) return false;
    for (std::size_t k = 0; k < t.count; ++k) {
      const Scalar x = m.points[2 * (t.first + k)];
      const Scalar y = m.points[2 * (t.first + k) + 1];
      if (!detail::is_finite(x) || !detail::is_finite(y)) return false;
      if (k > 0 && !(m.points[2 * (t.first + k - 1)] < x)) return false;
    }
    return true;
  };
  for (std::size_t i = 0; i < m.num_inputs; ++i) {
    const auto& in = m.inputs[i];
    // An input's range only matters for lock_range (FCL files may leave it -inf .. inf).
    if (!(in.lock_range ? range_ok(in.min, in.max) : in.min < in.max))
      return {"input range must be min < max (finite with lock-range)", i,
              ModelError::Where::Input};
    if (in.num_terms > Cap::terms)
      return {"more input terms than the capacity", i, ModelError::Where::Input};
    for (std::size_t t = 0; t < in.num_terms; ++t)
      if (!term_ok(in.terms[t]))
        return {"invalid input term parameters", i, ModelError::Where::Input};
  }
  const bool merged = m.merges_activations();
  for (std::size_t o = 0; o < m.num_outputs; ++o) {
    const auto& out = m.outputs[o];
    const bool sugeno = is_sugeno(out.defuzzifier);
    // A weighted defuzzifier over constant/linear terms never reads the range (fuzzylite
    // accepts any, e.g. the zero width of [0 0] some .fis exports write).
    const bool range_unused =
        sugeno && !out.lock_range &&
        (out.num_terms == 0 || out.terms[0].kind != OutputTermKind::Membership);
    if (!(range_unused                ? out.min <= out.max
          : sugeno && !out.lock_range ? out.min < out.max
                                      : range_ok(out.min, out.max)))
      return {
          "output range must be finite with min < max (Sugeno outputs without lock-range: "
          "min < max, or min <= max over constant/linear terms)",
          o, ModelError::Where::Output};
    if (out.num_terms > Cap::terms)
      return {"more output terms than the capacity", o, ModelError::Where::Output};
    if (!sugeno && (out.resolution < 1 || out.resolution > 100000000))
      return {"resolution must be in 1..1e8", o, ModelError::Where::Output};
    if (out.default_value == out.default_value && !detail::is_finite(out.default_value))
      return {"default value must be finite or NaN", o, ModelError::Where::Output};
    if (!sugeno && out.exact_centroid) {
      if (out.defuzzifier != Defuzzifier::Centroid)
        return {"the exact centroid applies to the centroid only", o, ModelError::Where::Output};
      if (!(out.aggregation == SNorm::UnboundedSum ||
            (out.aggregation == SNorm::Maximum && merged)))
        return {
            "the exact centroid needs Maximum or UnboundedSum aggregation and one "
            "Minimum or Product implication",
            o, ModelError::Where::Output};
    }
    if (out.group_by_term && (!sugeno || out.merge_equal_singletons))
      return {"grouping by term needs a weighted defuzzifier and no merging of singletons", o,
              ModelError::Where::Output};
    // A weighted defuzzifier over monotonic membership terms is Tsukamoto's method.
    const bool tsukamoto =
        sugeno && out.num_terms > 0 && out.terms[0].kind == OutputTermKind::Membership;
    for (std::size_t t = 0; t < out.num_terms; ++t) {
      const auto& term = out.terms[t];
      const bool membership = term.kind == OutputTermKind::Membership;
      if (membership != tsukamoto && sugeno)
        return {
            "Sugeno defuzzifiers need constant/linear terms (or, for Tsukamoto, monotonic "
            "Ramp, Sigmoid, SShape, ZShape, Concave or Arc terms), not a mix",
            o, ModelError::Where::Output};
      if (!sugeno && !membership)
        return {"integral defuzzifiers need membership terms, not constant/linear/function ones", o,
                ModelError::Where::Output};
      if (out.merge_equal_singletons &&
          (membership || !out.has_aggregation || term.kind == OutputTermKind::Function))
        return {"merging equal singletons needs constant/linear terms and an aggregation", o,
                ModelError::Where::Output};
      if (tsukamoto && !is_monotonic(term.membership))
        return {"Tsukamoto terms must be Ramp, Sigmoid, SShape, ZShape, Concave or Arc", o,
                ModelError::Where::Output};
      // mu(z) = w has no solution for w > 0 (fuzzylite 8 divides by the height: inf or NaN).
      if (tsukamoto && !(term.membership.height > Scalar(0)))
        return {"a Tsukamoto term needs a height > 0 (of height 0 it reaches no degree w > 0)", o,
                ModelError::Where::Output};
      if (membership && term.membership.shape == Shape::Function)
        return {
            "a Function term of an output must be a Takagi-Sugeno term (a weighted "
            "defuzzifier); an integral defuzzifier would sample it",
            o, ModelError::Where::Output};
      if (term.kind == OutputTermKind::Function && !formula_ok(term.membership, false))
        return {"an output's formula must be well formed and read the inputs only (not x)", o,
                ModelError::Where::Output};
      if (membership && !term_ok(term.membership))
        return {"invalid output term parameters", o, ModelError::Where::Output};
      if (membership && out.exact_centroid && !is_piecewise_linear(term.membership))
        return {"the exact centroid needs piecewise-linear terms of height 1", o,
                ModelError::Where::Output};
      if (!membership)
        for (std::size_t c = 0; c < m.coefficients_of(term.kind); ++c)
          if (!detail::is_finite(term.coefficients[c]))
            return {"non-finite output coefficient", o, ModelError::Where::Output};
    }
  }
  for (std::size_t r = 0; r < m.num_rules; ++r) {
    const auto& rule = m.rules[r];
    if (!(rule.weight >= Scalar(0) && rule.weight <= Scalar(1)))
      return {"rule weight must be in [0, 1]", r, ModelError::Where::Rule};
    if (rule.block >= m.num_blocks) return {"rule of an unknown block", r, ModelError::Where::Rule};
    const RuleBlock& block = m.blocks[rule.block];
    if (static_cast<std::size_t>(rule.first_token) + rule.num_tokens > m.num_tokens ||
        rule.num_tokens > Cap::rule_tokens ||
        static_cast<std::size_t>(rule.first_conclusion) + rule.num_conclusions > m.num_conclusions)
      return {"rule refers to storage it does not own", r, ModelError::Where::Rule};
    std::size_t depth = 0;
    for (std::size_t k = 0; k < rule.num_tokens; ++k) {
      const Token& tok = m.tokens[rule.first_token + k];
      if (tok.kind == Token::Kind::Proposition) {
        if (tok.input >= m.num_inputs || tok.num_hedges > kMaxHedges)
          return {"rule names an unknown input", r, ModelError::Where::Rule};
        const bool any = tok.num_hedges > 0 && tok.hedges[tok.num_hedges - 1] == Hedge::Any;
        if (!any && tok.term >= m.inputs[tok.input].num_terms)
          return {"rule names an unknown input term", r, ModelError::Where::Rule};
        if (tok.power_tenths > 100 || (any && tok.power_tenths != 0) ||
            (tok.power_tenths != 0 && !m.power_hedges))
          return {"a power hedge must be .01 to 1.00 on a term, with power_hedges set", r,
                  ModelError::Where::Rule};
        ++depth;
      } else if (tok.kind == Token::Kind::OutputProposition) {
        if (!m.chained || tok.input >= m.num_outputs || tok.num_hedges > kMaxHedges)
          return {"rule names an unknown output in its antecedent", r, ModelError::Where::Rule};
        const bool any = tok.num_hedges > 0 && tok.hedges[tok.num_hedges - 1] == Hedge::Any;
        if (!any && tok.term >= m.outputs[tok.input].num_terms)
          return {"rule names an unknown output term in its antecedent", r,
                  ModelError::Where::Rule};
        if (tok.power_tenths > 100 || (any && tok.power_tenths != 0) ||
            (tok.power_tenths != 0 && !m.power_hedges))
          return {"a power hedge must be .01 to 1.00 on a term, with power_hedges set", r,
                  ModelError::Where::Rule};
        ++depth;
      } else {
        if (depth < 2) return {"malformed antecedent", r, ModelError::Where::Rule};
        if (tok.kind == Token::Kind::And ? !block.has_conjunction : !block.has_disjunction)
          return {"rule uses 'and'/'or' but its block has no conjunction/disjunction", r,
                  ModelError::Where::Rule};
        --depth;
      }
    }
    if (depth != 1) return {"malformed antecedent", r, ModelError::Where::Rule};
    if (rule.num_conclusions == 0) return {"rule has no consequent", r, ModelError::Where::Rule};
    for (std::size_t k = 0; k < rule.num_conclusions; ++k) {
      const Conclusion& c = m.conclusions[rule.first_conclusion + k];
      if (c.output >= m.num_outputs || c.term >= m.outputs[c.output].num_terms ||
          c.num_hedges > kMaxHedges)
        return {"rule names an unknown output term", r, ModelError::Where::Rule};
      for (std::size_t j = 0; j < k; ++j)
        if (m.conclusions[rule.first_conclusion + j].output == c.output)
          return {"rule concludes twice on one output", r, ModelError::Where::Rule};
      if (!is_sugeno(m.outputs[c.output].defuzzifier) && !block.has_implication)
        return {"a Mamdani output needs an implication operator in the rule's block", r,
                ModelError::Where::Rule};
      if (c.power_tenths > 100 ||
          (c.power_tenths != 0 && (!is_sugeno(m.outputs[c.output].defuzzifier) || !m.power_hedges)))
        return {
            "a power hedge (.01 to 1.00, with power_hedges set) concludes on Sugeno outputs only",
            r, ModelError::Where::Rule};
    }
  }
  return {};
}

}  // namespace fuzzypid::fuzzy
