// A two-input, multi-output zero-order Takagi-Sugeno fuzzy system whose rules are tables: the
// structure of the paper's supervisor (section 5, Tables 2-4, Eq. 8).
#pragma once

#include <array>
#include <cstddef>

#include "fuzzypid/fuzzy/linguistic_variable.hpp"
#include "fuzzypid/fuzzy/operators.hpp"
#include "fuzzypid/fuzzy/rule_table.hpp"
#include "fuzzypid/scalar.hpp"
#include "fuzzypid/status.hpp"

namespace fuzzypid::fuzzy {

// The outcome of one inference: the crisp outputs, a status, and the fuzzified inputs from which
// every rule's firing strength can be read back without allocation (to debug a rule base).
template <class Scalar, std::size_t NE, std::size_t NEC, std::size_t NOut>
struct TskResult {
  std::array<Scalar, NOut> output{};  // 0 for every output when no rule fired
  Status status = Status::Ok;         // Ok, NoRuleFired or NonFiniteInput
  Fuzzified<Scalar, NE> e;            // degrees of e in each of its terms
  Fuzzified<Scalar, NEC> ec;          // degrees of ec in each of its terms
  Scalar total_strength = Scalar(0);  // sum of all firing strengths
  Conjunction conjunction = Conjunction::Minimum;

  // Firing strength of rule (i, j): "IF e is E_i AND ec is EC_j".
  constexpr Scalar firing_strength(std::size_t i, std::size_t j) const noexcept {
    return conjoin(conjunction, e.degree[i], ec.degree[j]);
  }
};

template <class Scalar, std::size_t NE, std::size_t NEC, std::size_t NOut>
struct TskSystem {
  FUZZYPID_ASSERT_SCALAR(Scalar);
  static_assert(NOut >= 1, "a fuzzy system needs an output");

  using Result = TskResult<Scalar, NE, NEC, NOut>;
  static constexpr std::size_t num_outputs = NOut;

  LinguisticVariable<Scalar, NE> e;    // first input (the paper's joint error, universe units)
  LinguisticVariable<Scalar, NEC> ec;  // second input (the error rate, universe units)
  std::array<RuleTable<Scalar, NE, NEC>, NOut> consequents{};  // one table per output
  Conjunction conjunction = Conjunction::Minimum;
  TskDefuzzifier defuzzifier = TskDefuzzifier::WeightedAverage;

  // True when both variables are valid and every consequent is finite.
  constexpr bool valid() const noexcept {
    if (!e.valid() || !ec.valid()) return false;
    for (const auto& table : consequents)
      for (const auto& row : table)
        for (Scalar c : row)
          if (!detail::is_finite(c)) return false;
    return true;
  }

  // Fires every rule and defuzzifies:
  //   w_ij = AND(mu_Ei(e), mu_ECj(ec)),  y = sum(w_ij c_ij) / sum(w_ij)   (Eq. 8)
  // or the plain weighted sum. Only rules whose antecedents both hold can contribute, so the loop
  // runs over the non-zero degrees only (at most 2 x 2 rules for a uniform partition). A NaN or
  // infinite input gives NonFiniteInput; no firing rule gives NoRuleFired; both with zero outputs.
  Result infer(Scalar e_value, Scalar ec_value) const noexcept {
    Result r;
    r.conjunction = conjunction;
    if (!detail::is_finite(e_value) || !detail::is_finite(ec_value)) {
      r.status = Status::NonFiniteInput;
      return r;
    }
    r.e = e.fuzzify(e_value);
    r.ec = ec.fuzzify(ec_value);
    std::array<Scalar, NOut> weighted{};
    Scalar total = Scalar(0);
    for (std::size_t i = r.e.first; i <= r.e.last && i < NE; ++i) {
      for (std::size_t j = r.ec.first; j <= r.ec.last && j < NEC; ++j) {
        const Scalar w = conjoin(conjunction, r.e.degree[i], r.ec.degree[j]);
        total += w;
        for (std::size_t o = 0; o < NOut; ++o) weighted[o] += w * consequents[o][i][j];
      }
    }
    r.total_strength = total;
    if (!(total > Scalar(0))) {
      r.status = Status::NoRuleFired;
      return r;
    }
    if (defuzzifier == TskDefuzzifier::WeightedAverage) {
      for (std::size_t o = 0; o < NOut; ++o) r.output[o] = weighted[o] / total;
    } else {
      r.output = weighted;
    }
    return r;
  }
};

}  // namespace fuzzypid::fuzzy
