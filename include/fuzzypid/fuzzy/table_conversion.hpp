// A loaded rule base of the paper's shape converted to the table system (TskSystem), which
// evaluates only the 2 x 2 rules a uniform partition can fire.
//
// The model qualifies when it has two inputs with NE and NEC terms and no lock-range, NOut
// outputs that are all weighted average (or all weighted sum) of constant terms with no default
// value, lock-range or hedges, one rule block whose conjunction is Minimum or Product, and
// exactly one rule "if e is E_i and ec is EC_j then o_1 is C_1 and ... o_NOut is C_NOut" (weight
// 1) per cell (i, j). Inputs whose terms form the uniform partition with shoulders of
// LinguisticVariable::uniform() (a trapezoid with infinite feet is a shoulder; peaks equal to
// within 1e-12 of the range) get its O(1) fuzzification; any other terms are kept as they are
// (LinguisticVariable::custom). Results then equal the engine's up to the order of summation
// (a few ulp).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

#include "fuzzypid/fuzzy/engine.hpp"
#include "fuzzypid/fuzzy/tsk_system.hpp"

namespace fuzzypid::fuzzy {

namespace table_detail {

template <class Scalar, std::size_t N, class Input>
bool is_uniform_partition(const Input& in) noexcept {
  const auto u = LinguisticVariable<Scalar, N>::uniform(in.min, in.max);
  const Scalar tol = Scalar(1e-12) * (in.max - in.min);
  const auto near = [&](Scalar a, Scalar b) { return std::fabs(a - b) <= tol; };
  const Scalar inf = detail::infinity<Scalar>();
  for (std::size_t k = 0; k < N; ++k) {
    const Term<Scalar>& t = in.terms[k];
    const Term<Scalar>& v = u.term(k);
    if (t.height != Scalar(1)) return false;
    if (k == 0) {
      const bool shoulder =
          (t.shape == Shape::LeftShoulder && near(t.p[0], v.p[0]) && near(t.p[1], v.p[1])) ||
          (t.shape == Shape::Trapezoid && t.p[0] == -inf && t.p[1] == -inf &&
           near(t.p[2], v.p[0]) && near(t.p[3], v.p[1]));
      if (!shoulder) return false;
    } else if (k + 1 == N) {
      const bool shoulder =
          (t.shape == Shape::RightShoulder && near(t.p[0], v.p[0]) && near(t.p[1], v.p[1])) ||
          (t.shape == Shape::Trapezoid && t.p[2] == inf && t.p[3] == inf && near(t.p[0], v.p[0]) &&
           near(t.p[1], v.p[1]));
      if (!shoulder) return false;
    } else if (!(t.shape == Shape::Triangle && near(t.p[0], v.p[0]) && near(t.p[1], v.p[1]) &&
                 near(t.p[2], v.p[2]))) {
      return false;
    }
  }
  return true;
}

template <class Scalar, std::size_t N, class Input>
LinguisticVariable<Scalar, N> variable(const Input& in) noexcept {
  if (is_uniform_partition<Scalar, N>(in))
    return LinguisticVariable<Scalar, N>::uniform(in.min, in.max);
  std::array<Term<Scalar>, N> terms{};
  for (std::size_t k = 0; k < N; ++k)
    terms[k] = in.terms[k];
  return LinguisticVariable<Scalar, N>::custom(in.min, in.max, terms);
}

}  // namespace table_detail

// Fills `out` from `m`; returns why the model does not qualify (nothing is written then).
template <class Scalar, class Cap, std::size_t NE, std::size_t NEC, std::size_t NOut>
ModelError to_table_system(const EngineModel<Scalar, Cap>& m,
                           TskSystem<Scalar, NE, NEC, NOut>& out) noexcept {
  using Where = ModelError::Where;
  if (const ModelError e = m.validate()) return e;
  if (m.num_inputs != 2 || m.inputs[0].num_terms != NE || m.inputs[1].num_terms != NEC)
    return {"the table system needs two inputs with NE and NEC terms", 0, Where::Model};
  if (m.num_outputs != NOut) return {"the table system needs NOut outputs", 0, Where::Model};
  for (std::size_t i = 0; i < 2; ++i) {
    const auto& in = m.inputs[i];
    if (in.lock_range || !detail::is_finite(in.min) || !detail::is_finite(in.max))
      return {"table-system inputs need a finite range without lock-range", i, Where::Input};
    for (std::size_t t = 0; t < in.num_terms; ++t)
      if (in.terms[t].shape == Shape::Discrete)
        return {"table-system inputs cannot hold Discrete terms", i, Where::Input};
  }
  const Defuzzifier d = m.outputs[0].defuzzifier;
  for (std::size_t o = 0; o < NOut; ++o) {
    const auto& v = m.outputs[o];
    if (v.defuzzifier != d || !is_sugeno(d))
      return {"table-system outputs are all weighted average or all weighted sum", o,
              Where::Output};
    if (v.lock_range || v.lock_previous || v.default_value == v.default_value)
      return {"table-system outputs have no lock-range, lock-previous or default value", o,
              Where::Output};
    for (std::size_t t = 0; t < v.num_terms; ++t)
      if (v.terms[t].kind != OutputTermKind::Constant)
        return {"table-system outputs need constant terms", o, Where::Output};
  }
  if (m.num_blocks != 1 || !m.blocks[0].has_conjunction ||
      (m.blocks[0].conjunction != TNorm::Minimum && m.blocks[0].conjunction != TNorm::Product))
    return {"the table system needs one rule block with a Minimum or Product conjunction", 0,
            Where::Model};
  if (m.num_rules != NE * NEC) return {"the table system needs one rule per cell", 0, Where::Model};
  TskSystem<Scalar, NE, NEC, NOut> s{};
  std::array<std::array<bool, NEC>, NE> seen{};
  for (std::size_t r = 0; r < m.num_rules; ++r) {
    const Rule<Scalar>& rule = m.rules[r];
    const Token* t = &m.tokens[rule.first_token];
    const bool shape = rule.weight == Scalar(1) && rule.num_tokens == 3 &&
                       t[0].kind == Token::Kind::Proposition && t[0].input == 0 &&
                       t[0].num_hedges == 0 && t[1].kind == Token::Kind::Proposition &&
                       t[1].input == 1 && t[1].num_hedges == 0 && t[2].kind == Token::Kind::And &&
                       rule.num_conclusions == NOut;
    if (!shape)
      return {"table-system rules are 'if e is E_i and ec is EC_j then' every output, weight 1", r,
              Where::Rule};
    if (seen[t[0].term][t[1].term]) return {"two rules for one cell", r, Where::Rule};
    seen[t[0].term][t[1].term] = true;
    std::array<bool, NOut> concluded{};
    for (std::size_t k = 0; k < NOut; ++k) {
      const Conclusion& c = m.conclusions[rule.first_conclusion + k];
      if (c.num_hedges != 0 || concluded[c.output])
        return {"table-system conclusions have no hedges", r, Where::Rule};
      concluded[c.output] = true;
      s.consequents[c.output][t[0].term][t[1].term] =
          m.outputs[c.output].terms[c.term].coefficients[0];
    }
  }
  s.e = table_detail::variable<Scalar, NE>(m.inputs[0]);
  s.ec = table_detail::variable<Scalar, NEC>(m.inputs[1]);
  s.conjunction = m.blocks[0].conjunction;
  s.defuzzifier = d;
  if (!s.valid()) return {"the converted table system is not valid", 0, Where::Model};
  out = s;
  return {};
}

}  // namespace fuzzypid::fuzzy
