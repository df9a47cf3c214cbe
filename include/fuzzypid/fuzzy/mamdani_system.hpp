// A two-input, multi-output Mamdani fuzzy system whose rules are tables (the MATLAB-style
// counterpart of TskSystem): each cell names an output term instead of a crisp value.
//
// Per output o and inference:
//   w_ij   = AND(mu_Ei(e), mu_ECj(ec))                       rule strength (min or product)
//   a_t    = max { w_ij : consequents[o][i][j] == t }        activation of output term t
//   F(y)   = max_t IMP(mu_t(y), a_t)                         implication min or product
//   output = centroid of F over the output's range [min, max]
// Taking the largest strength per term before implication is exact for max aggregation, because
// min(mu, w) and mu w are non-decreasing in w. The centroid is computed exactly (closed form, all
// output terms piecewise linear) or by fuzzylite's midpoint rule at a fixed resolution.
#pragma once

#include <array>
#include <cstddef>

#include "fuzzypid/fuzzy/defuzzify.hpp"
#include "fuzzypid/fuzzy/linguistic_variable.hpp"
#include "fuzzypid/fuzzy/membership.hpp"
#include "fuzzypid/fuzzy/operators.hpp"
#include "fuzzypid/fuzzy/rule_table.hpp"
#include "fuzzypid/scalar.hpp"
#include "fuzzypid/status.hpp"

namespace fuzzypid::fuzzy {

// How the centroid integral is evaluated.
enum class CentroidMethod : std::uint8_t {
  Exact,    // closed form; requires piecewise-linear output terms
  Sampled,  // fuzzylite's Centroid: `resolution` midpoint samples
};

// An output variable of a Mamdani system: NTerms terms over the range [min, max] in which the
// centroid is taken (mass of a term outside the range is ignored, as in MATLAB and fuzzylite).
template <class Scalar, std::size_t NTerms>
struct OutputVariable {
  Scalar min = Scalar(0);
  Scalar max = Scalar(1);
  std::array<Term<Scalar>, NTerms> terms{};

  constexpr bool valid() const noexcept {
    if (!(detail::is_finite(min) && detail::is_finite(max) && min < max)) return false;
    for (const auto& t : terms)
      if (!t.valid()) return false;
    return true;
  }
};

template <class Scalar, std::size_t NE, std::size_t NEC, std::size_t NTerms, std::size_t NOut>
struct MamdaniResult {
  std::array<Scalar, NOut> output{};  // 0 for an output whose aggregated set is empty
  Status status = Status::Ok;         // Ok, NoRuleFired (any output empty) or NonFiniteInput
  Fuzzified<Scalar, NE> e;            // degrees of e in each of its terms
  Fuzzified<Scalar, NEC> ec;          // degrees of ec in each of its terms
  // activation[o][t]: the largest strength of the rules concluding "output o is term t".
  std::array<std::array<Scalar, NTerms>, NOut> activation{};
  Conjunction conjunction = Conjunction::Minimum;

  // Firing strength of rule (i, j): "IF e is E_i AND ec is EC_j".
  constexpr Scalar firing_strength(std::size_t i, std::size_t j) const noexcept {
    return conjoin(conjunction, e.degree[i], ec.degree[j]);
  }
};

template <class Scalar, std::size_t NE, std::size_t NEC, std::size_t NTerms, std::size_t NOut>
struct MamdaniSystem {
  FUZZYPID_ASSERT_SCALAR(Scalar);
  static_assert(NOut >= 1, "a fuzzy system needs an output");
  static_assert(NTerms >= 1, "an output variable needs a term");

  using Result = MamdaniResult<Scalar, NE, NEC, NTerms, NOut>;
  static constexpr std::size_t num_outputs = NOut;

  LinguisticVariable<Scalar, NE> e;    // first input
  LinguisticVariable<Scalar, NEC> ec;  // second input
  std::array<OutputVariable<Scalar, NTerms>, NOut> outputs{};
  // consequents[o][i][j]: index of the term of output o concluded by rule (i, j); < 0 = no rule.
  std::array<TermTable<NE, NEC>, NOut> consequents{};
  Conjunction conjunction = Conjunction::Minimum;
  Implication implication = Implication::Minimum;
  CentroidMethod centroid = CentroidMethod::Exact;
  int resolution = 100;  // samples for CentroidMethod::Sampled (fuzzylite's default)

  // True when the variables are valid, every consequent index is < NTerms, the resolution is
  // positive and (for the exact centroid) every output term is piecewise linear.
  constexpr bool valid() const noexcept {
    if (!e.valid() || !ec.valid()) return false;
    if (centroid == CentroidMethod::Sampled && resolution < 1) return false;
    for (const auto& out : outputs) {
      if (!out.valid()) return false;
      if (centroid == CentroidMethod::Exact)
        for (const auto& t : out.terms)
          if (!is_piecewise_linear(t)) return false;
    }
    for (const auto& table : consequents)
      for (const auto& row : table)
        for (int c : row)
          if (c >= static_cast<int>(NTerms)) return false;
    return true;
  }

  // Fires the rules, aggregates and takes each output's centroid. A NaN or infinite input gives
  // NonFiniteInput; an output whose aggregated set has no area in its range (no rule fired for
  // it) is 0 and gives NoRuleFired. Only the rules whose antecedents both hold are visited.
  Result infer(Scalar e_value, Scalar ec_value) const noexcept {
    Result r;
    r.conjunction = conjunction;
    if (!detail::is_finite(e_value) || !detail::is_finite(ec_value)) {
      r.status = Status::NonFiniteInput;
      return r;
    }
    r.e = e.fuzzify(e_value);
    r.ec = ec.fuzzify(ec_value);
    for (std::size_t i = r.e.first; i <= r.e.last && i < NE; ++i) {
      for (std::size_t j = r.ec.first; j <= r.ec.last && j < NEC; ++j) {
        const Scalar w = conjoin(conjunction, r.e.degree[i], r.ec.degree[j]);
        if (!(w > Scalar(0))) continue;
        for (std::size_t o = 0; o < NOut; ++o) {
          const int t = consequents[o][i][j];
          if (t >= 0) r.activation[o][t] = detail::max(r.activation[o][t], w);
        }
      }
    }
    for (std::size_t o = 0; o < NOut; ++o) {
      const Scalar y = defuzzify(o, r.activation[o]);
      if (y == y) {
        r.output[o] = y;
      } else {
        r.status = Status::NoRuleFired;
      }
    }
    return r;
  }

  // Centroid of output o given its term activations; NaN when the aggregated set is empty.
  Scalar defuzzify(std::size_t o, const std::array<Scalar, NTerms>& activation) const noexcept {
    std::array<Activation<Scalar>, NTerms> active{};
    std::size_t n = 0;
    for (std::size_t t = 0; t < NTerms; ++t)
      if (activation[t] > Scalar(0)) active[n++] = {&outputs[o].terms[t], activation[t]};
    if (n == 0) return std::numeric_limits<Scalar>::quiet_NaN();
    const AggregatedSet<Scalar> set{active.data(), n, implication, Aggregation::Maximum};
    const OutputVariable<Scalar, NTerms>& out = outputs[o];
    if (centroid == CentroidMethod::Sampled)
      return centroid_sampled(set, out.min, out.max, resolution);
    std::array<Scalar, 6 * NTerms + 2> breakpoints{};
    std::array<Scalar, 2 * NTerms> lines{};
    std::array<Scalar, NTerms*(NTerms - 1) / 2 + 1> crossings{};
    return centroid_exact(set, out.min, out.max, breakpoints.data(), lines.data(), crossings.data(),
                          {breakpoints.size(), lines.size(), crossings.size()});
  }
};

}  // namespace fuzzypid::fuzzy
