// A two-input, multi-output zero-order Takagi-Sugeno fuzzy system whose rules are tables: the
// structure of the paper's supervisor (section 5, Tables 2-4, Eq. 8).
//
// One inference, for inputs e and ec (universe units):
//   mu_Ei(e), mu_ECj(ec)          fuzzification
//   w_ij = AND(mu_Ei, mu_ECj)     firing strength, AND = minimum or product
//   y_o  = sum(w_ij c_o,ij) / sum(w_ij)   (weighted average, Eq. 8) or sum(w_ij c_o,ij)
// With two uniform partitions (LinguisticVariable::uniform) at most two adjacent terms of each
// input hold a value, so the inference fires one 2 x 2 block of rules (degrees of 0 included,
// which add exact zeros) and costs one division, 1 / sum(w). A custom partition fires every rule.
//
// The system is an immutable model: infer() is const, thread-safe and keeps no state, so one
// instance serves every joint (see supervisor/supervisor.hpp for the supervisor concept it fulfils
// when NOut is 3).
#pragma once

#include <array>
#include <cstddef>
#include <utility>

#include "fuzzypid/fuzzy/consequent_table.hpp"
#include "fuzzypid/fuzzy/linguistic_variable.hpp"
#include "fuzzypid/fuzzy/operators.hpp"
#include "fuzzypid/scalar.hpp"
#include "fuzzypid/status.hpp"

namespace fuzzypid::fuzzy {

// What an inference fired, for debugging a rule base: the degrees of both inputs in every term
// and the total firing strength. Filled only when the caller passes one to infer(); no
// allocation.
template <class Scalar, std::size_t NE, std::size_t NEC>
struct TskTrace {
  Fuzzified<Scalar, NE> e;            // degrees of e in each of its terms
  Fuzzified<Scalar, NEC> ec;          // degrees of ec in each of its terms
  Scalar total_strength = Scalar(0);  // sum of all firing strengths
  Conjunction conjunction = Conjunction::Minimum;

  // Firing strength of rule (i, j): "IF e is E_i AND ec is EC_j".
  constexpr Scalar firing_strength(std::size_t i, std::size_t j) const noexcept {
    const Scalar a = e.degree[i];
    const Scalar b = ec.degree[j];
    return conjunction == Conjunction::Minimum ? detail::min(a, b) : a * b;
  }
};

// The outcome of one inference with its trace, as one value (set-up code, tools and tests).
template <class Scalar, std::size_t NE, std::size_t NEC, std::size_t NOut>
struct TskResult : TskTrace<Scalar, NE, NEC> {
  std::array<Scalar, NOut> output{};  // 0 for every output when no rule fired
  Status status = Status::Ok;         // Ok, NoRuleFired or NonFiniteInput
};

template <class Scalar, std::size_t NE, std::size_t NEC, std::size_t NOut>
struct TskSystem {
  FUZZYPID_ASSERT_SCALAR(Scalar);
  static_assert(NOut >= 1, "a fuzzy system needs an output");

  using Trace = TskTrace<Scalar, NE, NEC>;
  using Result = TskResult<Scalar, NE, NEC, NOut>;
  using Output = std::array<Scalar, NOut>;
  // Per-caller scratch of the supervisor concept: a table system needs none.
  struct Workspace {};
  static constexpr std::size_t num_outputs = NOut;

  LinguisticVariable<Scalar, NE> e;    // first input (the paper's joint error, universe units)
  LinguisticVariable<Scalar, NEC> ec;  // second input (the error rate, universe units)
  std::array<ConsequentTable<Scalar, NE, NEC>, NOut> consequents{};  // one table per output
  Conjunction conjunction = Conjunction::Minimum;                    // Minimum or Product
  TskDefuzzifier defuzzifier = TskDefuzzifier::WeightedAverage;

  // True when both variables are valid, the conjunction is Minimum or Product, the defuzzifier
  // WeightedAverage or WeightedSum and every consequent is finite.
  constexpr bool valid() const noexcept {
    if (!e.valid() || !ec.valid()) return false;
    if (conjunction != Conjunction::Minimum && conjunction != Conjunction::Product) return false;
    if (defuzzifier != TskDefuzzifier::WeightedAverage &&
        defuzzifier != TskDefuzzifier::WeightedSum)
      return false;
    for (const auto& table : consequents)
      for (const auto& row : table)
        for (Scalar c : row)
          if (!detail::is_finite(c)) return false;
    return true;
  }

  constexpr Workspace make_workspace() const noexcept { return {}; }

  // One inference into `output`. A NaN or infinite input gives NonFiniteInput, no firing rule
  // NoRuleFired, both with zero outputs; else Ok.
  [[nodiscard]] constexpr Status infer(Scalar e_value, Scalar ec_value, Workspace& /*unused*/,
                                       Output& output) const noexcept {
    return run<false>(e_value, ec_value, output, nullptr);
  }

  // The same inference, also writing what fired into `trace`.
  [[nodiscard]] constexpr Status infer(Scalar e_value, Scalar ec_value, Workspace& /*unused*/,
                                       Output& output, Trace& trace) const noexcept {
    return run<true>(e_value, ec_value, output, &trace);
  }

  // The same inference returned as one value with its trace.
  constexpr Result infer(Scalar e_value, Scalar ec_value) const noexcept {
    Result r;
    r.status = run<true>(e_value, ec_value, r.output, static_cast<Trace*>(&r));
    return r;
  }

 private:
  template <bool WithTrace>
  constexpr Status run(Scalar x, Scalar y, Output& output, Trace* trace) const noexcept {
    if constexpr (WithTrace) {
      *trace = Trace{};
      trace->conjunction = conjunction;
    }
    if (!detail::is_finite(x) || !detail::is_finite(y)) {
      output = {};
      return Status::NonFiniteInput;
    }
    if (e.is_uniform() && ec.is_uniform()) {
      const auto a = e.locate(x);
      const auto b = ec.locate(y);
      if constexpr (WithTrace) {
        trace->e = e.fuzzify(x);
        trace->ec = ec.fuzzify(y);
      }
      return conjunction == Conjunction::Minimum
                 ? fire_block<WithTrace, Conjunction::Minimum>(a, b, output, trace)
                 : fire_block<WithTrace, Conjunction::Product>(a, b, output, trace);
    }
    return run_custom<WithTrace>(x, y, output, trace);
  }

  // Custom partitions: every term evaluated, every rule fired. Out of line, so the uniform path
  // of a controller's tick stays small.
  template <bool WithTrace>
  [[gnu::noinline]] constexpr Status run_custom(Scalar x, Scalar y, Output& output,
                                                Trace* trace) const noexcept {
    const Fuzzified<Scalar, NE> fe = e.fuzzify(x);
    const Fuzzified<Scalar, NEC> fec = ec.fuzzify(y);
    if constexpr (WithTrace) {
      trace->e = fe;
      trace->ec = fec;
    }
    return conjunction == Conjunction::Minimum
               ? fire<WithTrace, Conjunction::Minimum, NE, NEC>(fe.degree.data(), 0,
                                                                fec.degree.data(), 0, output, trace)
               : fire<WithTrace, Conjunction::Product, NE, NEC>(
                     fe.degree.data(), 0, fec.degree.data(), 0, output, trace);
  }

  // Fires the 2 x 2 block of rules (k .. k + 1) x (m .. m + 1) of two uniform partitions, in rule
  // order, and defuzzifies. Degrees of 0 fire rules of strength 0, which add exact zeros.
  template <bool WithTrace, Conjunction Op>
  constexpr Status fire_block(const typename LinguisticVariable<Scalar, NE>::Adjacent& a,
                              const typename LinguisticVariable<Scalar, NEC>::Adjacent& b,
                              Output& output, Trace* trace) const noexcept {
    Scalar w00, w01, w10, w11;
    if constexpr (Op == Conjunction::Minimum) {
      w00 = detail::min(a.lower, b.lower);
      w01 = detail::min(a.lower, b.upper);
      w10 = detail::min(a.upper, b.lower);
      w11 = detail::min(a.upper, b.upper);
    } else {
      w00 = a.lower * b.lower;
      w01 = a.lower * b.upper;
      w10 = a.upper * b.lower;
      w11 = a.upper * b.upper;
    }
    const Scalar total = w00 + w01 + w10 + w11;
    if constexpr (WithTrace) trace->total_strength = total;
    if (!(total > Scalar(0))) {
      output = {};
      return Status::NoRuleFired;
    }
    const Scalar scale = defuzzifier == TskDefuzzifier::WeightedAverage
                             ? Scalar(1) / total  // the inference's one division
                             : Scalar(1);
    const std::size_t i = a.k;
    const std::size_t j = b.k;
    const auto defuzzify = [&](std::size_t o) {
      const Scalar* row = consequents[o][i].data() + j;
      const Scalar* next = consequents[o][i + 1].data() + j;
      output[o] = (w00 * row[0] + w01 * row[1] + w10 * next[0] + w11 * next[1]) * scale;
    };
    unrolled(defuzzify, std::make_index_sequence<NOut>{});
    return Status::Ok;
  }

  // f(0), ..., f(NOut - 1), unrolled at compile time (three outputs in the paper's system).
  template <class F, std::size_t... O>
  static constexpr void unrolled(F& f, std::index_sequence<O...>) noexcept {
    (f(O), ...);
  }

  // Fires rules (i0 .. i0 + Rows - 1) x (j0 .. j0 + Cols - 1) whose antecedent degrees are
  // de[0 .. Rows - 1] and dec[0 .. Cols - 1], in rule order, and defuzzifies.
  template <bool WithTrace, Conjunction Op, std::size_t Rows, std::size_t Cols>
  constexpr Status fire(const Scalar* de, std::size_t i0, const Scalar* dec, std::size_t j0,
                        Output& output, Trace* trace) const noexcept {
    Scalar total = Scalar(0);
    Output sum{};
    for (std::size_t i = 0; i < Rows; ++i) {
      for (std::size_t j = 0; j < Cols; ++j) {
        const Scalar w = Op == Conjunction::Minimum ? detail::min(de[i], dec[j]) : de[i] * dec[j];
        total += w;
        for (std::size_t o = 0; o < NOut; ++o)
          sum[o] += w * consequents[o][i0 + i][j0 + j];
      }
    }
    if constexpr (WithTrace) trace->total_strength = total;
    if (!(total > Scalar(0))) {
      output = {};
      return Status::NoRuleFired;
    }
    if (defuzzifier == TskDefuzzifier::WeightedAverage) {
      const Scalar inverse = Scalar(1) / total;  // the inference's one division
      for (std::size_t o = 0; o < NOut; ++o)
        output[o] = sum[o] * inverse;
    } else {
      output = sum;
    }
    return Status::Ok;
  }
};

}  // namespace fuzzypid::fuzzy
