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

// Only the crisp outputs and the status of an inference: what a controller's tick reads.
template <class Scalar, std::size_t NOut>
struct TskOutputs {
  std::array<Scalar, NOut> output{};  // 0 for every output when no rule fired
  Status status = Status::Ok;         // Ok, NoRuleFired or NonFiniteInput
};

template <class Scalar, std::size_t NE, std::size_t NEC, std::size_t NOut>
struct TskSystem {
  FUZZYPID_ASSERT_SCALAR(Scalar);
  static_assert(NOut >= 1, "a fuzzy system needs an output");

  using Result = TskResult<Scalar, NE, NEC, NOut>;
  using Outputs = TskOutputs<Scalar, NOut>;
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
    e.fuzzify_into(e_value, r.e);
    ec.fuzzify_into(ec_value, r.ec);
    const Sums sums = conjunction == Conjunction::Minimum ? fire<Conjunction::Minimum>(r.e, r.ec)
                                                          : fire<Conjunction::Product>(r.e, r.ec);
    r.total_strength = sums.total;
    r.status = defuzzify(sums, r.output);
    return r;
  }

  // infer()'s output and status, bit for bit, without the fuzzified inputs: for a controller's
  // tick, which reads nothing else. With two uniform partitions the degrees stay in registers (two
  // per input) instead of being written to and read back from a 190-byte result; any other
  // partition goes through infer().
  Outputs infer_outputs(Scalar e_value, Scalar ec_value) const noexcept {
    Outputs r;
    if (!e.is_uniform() || !ec.is_uniform()) {
      const Result full = infer(e_value, ec_value);
      r.output = full.output;
      r.status = full.status;
      return r;
    }
    if (!detail::is_finite(e_value) || !detail::is_finite(ec_value)) {
      r.status = Status::NonFiniteInput;
      return r;
    }
    const Sums sums = conjunction == Conjunction::Minimum
                          ? fire_adjacent<Conjunction::Minimum>(e_value, ec_value)
                          : fire_adjacent<Conjunction::Product>(e_value, ec_value);
    r.status = defuzzify(sums, r.output);
    return r;
  }

 private:
  struct Sums {
    std::array<Scalar, NOut> weighted;  // sum of w_ij c_ij per output
    Scalar total;                       // sum of w_ij
  };

  // NoRuleFired (outputs left at 0) when no rule fired, else Ok with the outputs defuzzified.
  Status defuzzify(const Sums& sums, std::array<Scalar, NOut>& output) const noexcept {
    const Scalar total = sums.total;
    if (!(total > Scalar(0))) return Status::NoRuleFired;
    if (defuzzifier == TskDefuzzifier::WeightedAverage) {
      for (std::size_t o = 0; o < NOut; ++o)
        output[o] = sums.weighted[o] / total;
    } else {
      output = sums.weighted;
    }
    return Status::Ok;
  }

  // Fires the rules (i, j) for i in [fe.first, fe.last], j in [fec.first, fec.last], row by row.
  // Spans of one or two terms (always the case for a uniform partition) take an unrolled path that
  // adds the same products in the same order as the general loop, so the sums are bit-identical.
  template <Conjunction Op>
  Sums fire(const Fuzzified<Scalar, NE>& fe, const Fuzzified<Scalar, NEC>& fec) const noexcept {
    if (fe.empty() || fec.empty()) return Sums{};
    const std::size_t i0 = fe.first;
    const std::size_t j0 = fec.first;
    if (fe.last - i0 > 1 || fec.last - j0 > 1) return fire_spans<Op>(fe, fec);
    return fire_span<Op>(&fe.degree[i0], fe.last - i0 + 1, &fec.degree[j0], fec.last - j0 + 1, i0,
                         j0);
  }

  // fire() for two uniform partitions, from each input's two adjacent degrees: the same spans
  // (a term holds the value when its degree is > 0) and the same degrees, hence the same sums.
  template <Conjunction Op>
  Sums fire_adjacent(Scalar e_value, Scalar ec_value) const noexcept {
    const auto a = e.locate(e_value);
    const auto b = ec.locate(ec_value);
    const Scalar de[2] = {a.lower, a.upper};
    const Scalar dec[2] = {b.lower, b.upper};
    const bool a_lo = a.lower > Scalar(0);
    const bool b_lo = b.lower > Scalar(0);
    const std::size_t rows = std::size_t{a_lo} + std::size_t{a.upper > Scalar(0)};
    const std::size_t cols = std::size_t{b_lo} + std::size_t{b.upper > Scalar(0)};
    if (rows == 0 || cols == 0) return Sums{};
    return fire_span<Op>(a_lo ? de : de + 1, rows, b_lo ? dec : dec + 1, cols, a_lo ? a.k : a.k + 1,
                         b_lo ? b.k : b.k + 1);
  }

  // Rules (i0 .. i0 + rows - 1) x (j0 .. j0 + cols - 1), rows and cols 1 or 2, whose antecedent
  // degrees are de[0 .. rows - 1] and dec[0 .. cols - 1].
  template <Conjunction Op>
  Sums fire_span(const Scalar* de, std::size_t rows, const Scalar* dec, std::size_t cols,
                 std::size_t i0, std::size_t j0) const noexcept {
    if (rows == 1)
      return cols == 1 ? fire_block<Op, 1, 1>(de, dec, i0, j0)
                       : fire_block<Op, 1, 2>(de, dec, i0, j0);
    return cols == 1 ? fire_block<Op, 2, 1>(de, dec, i0, j0)
                     : fire_block<Op, 2, 2>(de, dec, i0, j0);
  }

  // Rules (i0 .. i0 + Rows - 1) x (j0 .. j0 + Cols - 1), unrolled at compile time. Each output
  // accumulates its products in rule order, exactly as the general loop does.
  template <Conjunction Op, std::size_t Rows, std::size_t Cols>
  Sums fire_block(const Scalar* de, const Scalar* dec, std::size_t i0,
                  std::size_t j0) const noexcept {
    Scalar w[Rows][Cols];
    for (std::size_t i = 0; i < Rows; ++i)
      for (std::size_t j = 0; j < Cols; ++j)
        w[i][j] = conjoin(Op, de[i], dec[j]);
    Sums s;
    s.total = Scalar(0);
    for (std::size_t i = 0; i < Rows; ++i)
      for (std::size_t j = 0; j < Cols; ++j)
        s.total += w[i][j];
    for (std::size_t o = 0; o < NOut; ++o) {
      const RuleTable<Scalar, NE, NEC>& table = consequents[o];
      Scalar y = Scalar(0);
      for (std::size_t i = 0; i < Rows; ++i)
        for (std::size_t j = 0; j < Cols; ++j)
          y += w[i][j] * table[i0 + i][j0 + j];
      s.weighted[o] = y;
    }
    return s;
  }

  // The general loop, for partitions where more than two terms of a variable can hold. Out of
  // line so that infer() stays small enough to inline into a controller's tick.
  template <Conjunction Op>
  [[gnu::noinline]] Sums fire_spans(const Fuzzified<Scalar, NE>& fe,
                                    const Fuzzified<Scalar, NEC>& fec) const noexcept {
    Sums s{};
    for (std::size_t i = fe.first; i <= fe.last && i < NE; ++i) {
      for (std::size_t j = fec.first; j <= fec.last && j < NEC; ++j) {
        const Scalar w = conjoin(Op, fe.degree[i], fec.degree[j]);
        s.total += w;
        for (std::size_t o = 0; o < NOut; ++o)
          s.weighted[o] += w * consequents[o][i][j];
      }
    }
    return s;
  }
};

}  // namespace fuzzypid::fuzzy
