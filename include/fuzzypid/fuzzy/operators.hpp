// The fuzzy operators the engines offer: conjunction (AND) of antecedent degrees, implication,
// and the named choices of defuzzification.
#pragma once

#include <cstdint>

#include "fuzzypid/scalar.hpp"

namespace fuzzypid::fuzzy {

// How the degrees of "e is E_i" and "ec is EC_j" combine into a rule's firing strength.
enum class Conjunction : std::uint8_t {
  Minimum,  // w = min(mu_e, mu_ec)
  Product,  // w = mu_e * mu_ec
};

// How a Takagi-Sugeno system turns firing strengths and crisp consequents into its output.
enum class TskDefuzzifier : std::uint8_t {
  WeightedAverage,  // y = sum(w_r c_r) / sum(w_r)  -- the paper's center average, Eq. 8
  WeightedSum,      // y = sum(w_r c_r)
};

template <class Scalar>
constexpr Scalar conjoin(Conjunction op, Scalar a, Scalar b) noexcept {
  return op == Conjunction::Minimum ? detail::min(a, b) : a * b;
}

[[nodiscard]] constexpr const char* to_string(Conjunction c) noexcept {
  return c == Conjunction::Minimum ? "min" : "prod";
}

}  // namespace fuzzypid::fuzzy
