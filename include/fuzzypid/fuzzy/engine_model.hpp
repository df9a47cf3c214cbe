// The model of a run-time-sized fuzzy inference engine: inputs and outputs with their terms, rule
// blocks with their operators, rules as postfix antecedents and conclusions. Plain, immutable data:
// evaluation (fuzzy/engine.hpp) reads it and writes only into a workspace
// (fuzzy/engine_workspace.hpp), so one model serves many workspaces.
//
// Storage is the template parameter `Cap` (fuzzy/engine_storage.hpp: fixed-capacity arrays or
// arrays sized once to one model); copying between the two forms: fuzzy/engine_model_copy.hpp;
// validation: fuzzy/engine_model_validation.hpp.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "fuzzypid/enum_names.hpp"
#include "fuzzypid/fuzzy/defuzzify.hpp"
#include "fuzzypid/fuzzy/engine_storage.hpp"
#include "fuzzypid/fuzzy/formula.hpp"
#include "fuzzypid/fuzzy/membership.hpp"
#include "fuzzypid/fuzzy/operators.hpp"
#include "fuzzypid/scalar.hpp"

namespace fuzzypid::fuzzy {

template <class Scalar, class Cap = DefaultCapacity>
struct InputSpec {
  Name name{};
  Scalar min = Scalar(0);
  Scalar max = Scalar(1);
  bool lock_range = false;  // clamp the input into [min, max] before fuzzifying
  // false: a disabled input (fuzzylite's `enabled: false`): every proposition on it has degree 0
  // (hedges and `any` included), and its value is not read.
  bool enabled = true;
  std::size_t num_terms = 0;  // 0 allowed: an input no rule uses
  typename Cap::template Array<Term<Scalar>, Cap::terms> terms{};
  typename Cap::template Array<Name, Cap::terms> term_names{};
};

enum class OutputTermKind : std::uint8_t {
  Membership,  // a membership function (Mamdani)
  Constant,    // z = coefficients[0]
  Linear,      // z = sum_i coefficients[i] x_i + coefficients[num_inputs]
  Function,    // z = a formula of the inputs: `membership` is its Shape::Function term
};

template <class Scalar, class Cap = DefaultCapacity>
struct OutputTerm {
  OutputTermKind kind = OutputTermKind::Membership;
  Term<Scalar> membership{};
  // Sized models hold what the kind reads: num_inputs + 1 for Linear, 1 for Constant, none for
  // Membership terms.
  typename Cap::template Array<Scalar, Cap::inputs + 1> coefficients{};
};

template <class Scalar, class Cap = DefaultCapacity>
struct OutputSpec {
  Name name{};
  Scalar min = Scalar(0);
  Scalar max = Scalar(1);
  bool lock_range = false;  // clamp the crisp output into [min, max]
  // false: a disabled output (fuzzylite's `enabled: false`): conclusions on it are skipped (their
  // hedges do not modify the rule's running degree), propositions on it have degree 0, and its
  // value is 0 without a status (fuzzylite leaves it unchanged: NaN from the start).
  bool enabled = true;
  // When no rule concluded on the output, keep the last finite value of this workspace
  // (fuzzylite's lock-previous, FCL's DEFAULT := NC) instead of the default.
  bool lock_previous = false;
  // false: no aggregation operator (fuzzylite's `aggregation: none`, Sugeno outputs); only read
  // where a chained antecedent asks for a term's degree, which is then the sum of activations.
  bool has_aggregation = true;
  Scalar default_value = std::numeric_limits<Scalar>::quiet_NaN();  // when no rule fired
  Defuzzifier defuzzifier = Defuzzifier::Centroid;
  int resolution = 100;         // samples of the integral defuzzifiers
  bool exact_centroid = false;  // Centroid in closed form instead of sampled
  SNorm aggregation = SNorm::Maximum;
  // Octave's Sugeno aggregation (aggregate_output_sugeno): conclusions whose values z are equal
  // are one singleton, of the `aggregation` of their degrees, before the weighted average or sum.
  // Constant/linear terms only; false: every conclusion is a singleton of its own (fuzzylite).
  bool merge_equal_singletons = false;
  // fuzzylite 8's weighted defuzzification (Aggregated::grouped_terms): the activations of each
  // term fold into one degree w_t (the output's aggregation, their sum when it has none) and the
  // output is sum(w_t z_t(w_t)) over the concluded terms (divided by sum(w_t) for the weighted
  // average). Weighted defuzzifiers only; false: every activation is weighed on its own
  // (fuzzylite 6, Octave). See fuzzylite8_groups_by_term for when the two differ.
  bool group_by_term = false;
  std::size_t num_terms = 0;
  typename Cap::template Array<OutputTerm<Scalar, Cap>, Cap::terms> terms{};
  typename Cap::template Array<Name, Cap::terms> term_names{};
};

// One element of an antecedent in postfix order: a proposition pushes its degree, And/Or pop two
// degrees and push their conjunction/disjunction. OutputProposition tests an output variable
// (chained systems; `input` then holds the output's index).
struct Token {
  enum class Kind : std::uint8_t { Proposition, And, Or, OutputProposition };
  static constexpr std::uint8_t kAnyTerm = 0xFF;  // "x is any": no term
  Kind kind = Kind::Proposition;
  std::uint8_t input = 0;  // input index (output index for OutputProposition)
  std::uint8_t term = 0;   // index into the input's terms, or kAnyTerm
  std::uint8_t num_hedges = 0;
  std::array<Hedge, kMaxHedges> hedges{};  // as written, left to right
  // Octave's .fis hedge .dd (dd = 1..100): the degree raised to dd/10 before the hedges (which
  // then hold at most `not`); 0: none. fuzzylite has no such hedge (docs/rule_files.md).
  std::uint8_t power_tenths = 0;
};

// "output is [hedges] term". Without a power, the hedges act on the rule's running degree, which
// later conclusions of the rule inherit (fuzzylite's Consequent::modify). With Octave's power
// hedge .dd (Sugeno outputs only), the conclusion's degree is the rule's strength raised to
// 1/(dd/10), then the hedges, and the running degree is left alone (Octave's eval_rules_sugeno).
struct Conclusion {
  std::uint8_t output = 0;
  std::uint8_t term = 0;
  std::uint8_t num_hedges = 0;
  std::array<Hedge, kMaxHedges> hedges{};
  std::uint8_t power_tenths = 0;  // Octave's .fis hedge .dd; 0: none
};

template <class Scalar>
struct Rule {
  std::uint32_t first_token = 0;  // antecedent: tokens[first_token .. + num_tokens), postfix
  std::uint32_t num_tokens = 0;
  std::uint32_t first_conclusion = 0;  // conclusions[first_conclusion .. + num_conclusions)
  std::uint32_t num_conclusions = 0;
  std::uint32_t block = 0;
  Scalar weight = Scalar(1);
};

// The operators of a rule block. A block without a conjunction (disjunction) may not use `and`
// (`or`); one without implication may not conclude on a Mamdani output.
// Which of a block's rules fire (fuzzylite's activation methods), given their strengths w_r:
//   General        every rule with w_r > 0, in rule order
//   Proportional   w_r / sum of the block's w, then as General
//   Threshold      rules whose w_r compares true with `threshold` (and w_r > 0)
//   First, Last    the first (last) `count` rules with w_r > 0 and w_r >= threshold
//   Highest        the `count` rules of largest w_r > 0, largest first (ties as fuzzylite's
//   Lowest         heap orders them); Lowest: smallest first
enum class ActivationMethod : std::uint8_t {
  General,
  Proportional,
  Threshold,
  First,
  Last,
  Highest,
  Lowest
};
enum class Comparison : std::uint8_t {
  LessThan,
  LessThanOrEqualTo,
  EqualTo,
  NotEqualTo,
  GreaterThanOrEqualTo,
  GreaterThan
};
// fuzzylite's names (the .fll spelling).
inline constexpr std::array<EnumName<ActivationMethod>, 7> kActivationNames{
    {{ActivationMethod::General, "General"},
     {ActivationMethod::Proportional, "Proportional"},
     {ActivationMethod::Threshold, "Threshold"},
     {ActivationMethod::First, "First"},
     {ActivationMethod::Last, "Last"},
     {ActivationMethod::Highest, "Highest"},
     {ActivationMethod::Lowest, "Lowest"}}};
inline constexpr std::array<EnumName<Comparison>, 6> kComparisonNames{
    {{Comparison::LessThan, "<"},
     {Comparison::LessThanOrEqualTo, "<="},
     {Comparison::EqualTo, "=="},
     {Comparison::NotEqualTo, "!="},
     {Comparison::GreaterThanOrEqualTo, ">="},
     {Comparison::GreaterThan, ">"}}};

struct RuleBlock {
  Name name{};
  TNorm conjunction = TNorm::Minimum;
  SNorm disjunction = SNorm::Maximum;
  TNorm implication = TNorm::Minimum;
  bool has_conjunction = true;
  bool has_disjunction = true;
  bool has_implication = true;
  ActivationMethod activation = ActivationMethod::General;
  Comparison comparison = Comparison::GreaterThan;  // Threshold
  std::uint32_t count = 1;                          // First, Last, Highest, Lowest
  double threshold = 0.0;                           // Threshold, First, Last
};

// Whether fuzzylite 8 groups the activations of `out` by term (OutputSpec::group_by_term), as the
// .fll and .fcl readers set it: under a weighted defuzzifier when grouping changes the value, that
// is when z depends on the degree (Tsukamoto) or the aggregation is not a sum. Constant, linear
// and formula terms under no aggregation or UnboundedSum give the same value either way but for
// the order of the sums, and weigh every activation (fuzzylite 6's sums, bit for bit).
template <class Scalar, class Cap>
constexpr bool fuzzylite8_groups_by_term(const OutputSpec<Scalar, Cap>& out) noexcept {
  if (!is_sugeno(out.defuzzifier) || out.merge_equal_singletons) return false;
  const bool tsukamoto = out.num_terms > 0 && out.terms[0].kind == OutputTermKind::Membership;
  return tsukamoto || (out.has_aggregation && out.aggregation != SNorm::UnboundedSum);
}

template <class Scalar, class Cap = DefaultCapacity>
struct EngineModel {
  FUZZYPID_ASSERT_SCALAR(Scalar);
  using Capacity = Cap;

  Name name{};
  std::size_t num_inputs = 0;
  std::size_t num_outputs = 0;
  std::size_t num_rules = 0;
  std::size_t num_blocks = 1;
  std::size_t num_tokens = 0;
  std::size_t num_conclusions = 0;
  std::size_t num_points = 0;
  std::size_t num_steps = 0;  // formula steps of the Function terms
  bool chained = false;       // some antecedent tests an output (set by add_rule)
  // Some token or conclusion holds Octave's power hedge (set by add_rule): evaluation then takes
  // the instance that computes them (fuzzy::evaluate).
  bool power_hedges = false;
  template <class T, std::size_t N>
  using Array = typename Cap::template Array<T, N>;
  Array<InputSpec<Scalar, Cap>, Cap::inputs> inputs{};
  Array<OutputSpec<Scalar, Cap>, Cap::outputs> outputs{};
  Array<Rule<Scalar>, Cap::rules> rules{};
  Array<RuleBlock, Cap::blocks> blocks{};
  Array<Token, Cap::tokens> tokens{};
  Array<Conclusion, Cap::conclusions> conclusions{};
  Array<Scalar, 2 * Cap::points> points{};         // (x, y) pairs of the Discrete terms
  Array<FormulaStep<Scalar>, Cap::steps> steps{};  // the Function terms' formulas (formula.hpp)

  // Fixed-capacity models only: appends a rule to block `block` from its postfix antecedent and
  // its conclusions; false (model unchanged) when a capacity would be exceeded.
  template <class C = Cap, class = std::enable_if_t<!C::sized>>
  bool add_rule(const Token* antecedent, std::size_t n_tokens, const Conclusion* then,
                std::size_t n_conclusions, Scalar weight = Scalar(1),
                std::size_t block = 0) noexcept {
    if (num_rules == Cap::rules || n_tokens > Cap::rule_tokens ||
        num_tokens + n_tokens > Cap::tokens || num_conclusions + n_conclusions > Cap::conclusions)
      return false;
    Rule<Scalar>& r = rules[num_rules++];
    r.first_token = static_cast<std::uint32_t>(num_tokens);
    r.num_tokens = static_cast<std::uint32_t>(n_tokens);
    r.first_conclusion = static_cast<std::uint32_t>(num_conclusions);
    r.num_conclusions = static_cast<std::uint32_t>(n_conclusions);
    r.block = static_cast<std::uint32_t>(block);
    r.weight = weight;
    for (std::size_t k = 0; k < n_tokens; ++k) {
      chained = chained || antecedent[k].kind == Token::Kind::OutputProposition;
      power_hedges = power_hedges || antecedent[k].power_tenths != 0;
      tokens[num_tokens++] = antecedent[k];
    }
    for (std::size_t k = 0; k < n_conclusions; ++k) {
      power_hedges = power_hedges || then[k].power_tenths != 0;
      conclusions[num_conclusions++] = then[k];
    }
    return true;
  }

  // The largest number of terms of any input / output, and of tokens of any rule.
  std::size_t max_input_terms() const noexcept {
    std::size_t n = 0;
    for (std::size_t i = 0; i < num_inputs; ++i)
      n = detail::max(n, inputs[i].num_terms);
    return n;
  }
  std::size_t max_output_terms() const noexcept {
    std::size_t n = 0;
    for (std::size_t o = 0; o < num_outputs; ++o)
      n = detail::max(n, outputs[o].num_terms);
    return n;
  }
  std::size_t max_rule_tokens() const noexcept {
    std::size_t n = 0;
    for (std::size_t r = 0; r < num_rules; ++r)
      n = detail::max(n, static_cast<std::size_t>(rules[r].num_tokens));
    return n;
  }

  // True when every block shares one implication, Minimum or Product: Maximum aggregation then
  // keeps one activation per output term.
  bool merges_activations() const noexcept {
    for (std::size_t b = 0; b < num_blocks; ++b)
      if (blocks[b].implication != blocks[0].implication ||
          (blocks[b].implication != TNorm::Minimum && blocks[b].implication != TNorm::Product))
        return false;
    return true;
  }

  // True when some input or output is disabled (evaluation then checks each proposition's and
  // conclusion's variable; otherwise it skips those checks).
  bool has_disabled_variables() const noexcept {
    for (std::size_t i = 0; i < num_inputs; ++i)
      if (!inputs[i].enabled) return true;
    for (std::size_t o = 0; o < num_outputs; ++o)
      if (!outputs[o].enabled) return true;
    return false;
  }

  // The coefficients an output term of `kind` reads.
  std::size_t coefficients_of(OutputTermKind kind) const noexcept {
    return kind == OutputTermKind::Linear     ? num_inputs + 1
           : kind == OutputTermKind::Constant ? 1
                                              : 0;
  }

  // True when every array holds the counts it is read with (always, for a fixed capacity within
  // its limits; a sized model copied by copy_model()).
  bool storage_holds_counts() const noexcept {
    if (inputs.size() < num_inputs || outputs.size() < num_outputs || rules.size() < num_rules ||
        blocks.size() < num_blocks || tokens.size() < num_tokens ||
        conclusions.size() < num_conclusions || points.size() < 2 * num_points ||
        steps.size() < num_steps)
      return false;
    for (std::size_t i = 0; i < num_inputs; ++i)
      if (inputs[i].terms.size() < inputs[i].num_terms ||
          inputs[i].term_names.size() < inputs[i].num_terms)
        return false;
    for (std::size_t o = 0; o < num_outputs; ++o) {
      const auto& out = outputs[o];
      if (out.terms.size() < out.num_terms || out.term_names.size() < out.num_terms) return false;
      for (std::size_t t = 0; t < out.num_terms; ++t)
        if (out.terms[t].coefficients.size() < coefficients_of(out.terms[t].kind)) return false;
    }
    return true;
  }
};

}  // namespace fuzzypid::fuzzy
