// A run-time-sized fuzzy inference engine with a capacity fixed at compile time: the form a rule
// base loaded from a MATLAB .fis, fuzzylite .fll or IEC 61131-7 .fcl file takes (see
// fuzzypid/rulefile/rule_file.hpp and docs/rule_files.md).
//
// Capacity is the template parameter `Cap` (EngineCapacity<...>): inputs, outputs, terms per
// variable, rules, rule blocks, antecedent tokens and conclusions of all rules, points of Discrete
// terms. DefaultCapacity holds 8 inputs, 8 outputs, 64 terms per variable, 2,048 rules in 8 rule
// blocks; SmallCapacity is the paper's shape (2 inputs, 3 outputs, 7 terms, 49 rules) for
// microcontrollers. Memory: docs/rule_files.md (and sizeof in tests/unit/test_engine.cpp).
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
//                    Consequent::modify)
//   Mamdani output: activations (term, degree, the block's implication), aggregated by the
//     output's s-norm (folded from 0 in rule order), then centroid (sampled or exact), bisector,
//     mean/smallest/largest of maximum. With Maximum aggregation and a Minimum/Product implication
//     shared by all blocks, one activation per term holds the largest degree (exact, as both are
//     monotone).
//   Sugeno output (constant/linear terms): z_r = c or sum_i c_i x_i + c_0 per conclusion;
//     weighted average sum(w_r z_r) / sum(w_r) or weighted sum sum(w_r z_r).
//   Tsukamoto output (weighted defuzzifier over Ramp/Sigmoid/SShape/ZShape/Concave terms): z_r is
//   the
//     abscissa where the term reaches w_r (fuzzylite's inverses), then as Sugeno.
// The model is plain data; evaluation writes only into a separate workspace, is noexcept and
// allocates nothing. An output no rule concluded on takes its previous value when lock_previous
// and a previous evaluation with this workspace gave a finite value (kept in the workspace, so
// the model stays immutable), else its default value, or 0 with Status::NoRuleFired when the
// default is NaN (fuzzylite's "default: nan"); an output whose defuzzification has no area is 0
// with NoRuleFired too (fuzzylite gives NaN).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "fuzzypid/fuzzy/defuzzify.hpp"
#include "fuzzypid/fuzzy/membership.hpp"
#include "fuzzypid/fuzzy/operators.hpp"
#include "fuzzypid/scalar.hpp"
#include "fuzzypid/status.hpp"

namespace fuzzypid::fuzzy {

// The compile-time capacity of an engine model.
template <std::size_t Inputs, std::size_t Outputs, std::size_t Terms, std::size_t Rules,
          std::size_t Blocks, std::size_t Tokens, std::size_t Conclusions, std::size_t Points>
struct EngineCapacity {
  static_assert(Inputs >= 1 && Inputs <= 255 && Outputs >= 1 && Outputs <= 255,
                "inputs and outputs: 1..255");
  static_assert(Terms >= 1 && Terms <= 255, "terms per variable: 1..255");
  static_assert(Rules >= 1 && Blocks >= 1 && Tokens >= 1 && Conclusions >= 1, "empty capacity");
  static constexpr std::size_t inputs = Inputs;
  static constexpr std::size_t outputs = Outputs;
  static constexpr std::size_t terms = Terms;              // per variable
  static constexpr std::size_t rules = Rules;              // in all blocks
  static constexpr std::size_t blocks = Blocks;            // rule blocks
  static constexpr std::size_t tokens = Tokens;            // antecedent tokens of all rules
  static constexpr std::size_t conclusions = Conclusions;  // conclusions of all rules
  static constexpr std::size_t points = Points;            // (x, y) pairs of all Discrete terms
  static constexpr std::size_t rule_tokens = 63;           // tokens of one antecedent
};

using DefaultCapacity = EngineCapacity<8, 8, 64, 2048, 8, 16384, 8192, 4096>;
using SmallCapacity = EngineCapacity<2, 3, 7, 49, 1, 147, 147, 1>;

// The default capacity under short names.
inline constexpr std::size_t kMaxInputs = DefaultCapacity::inputs;
inline constexpr std::size_t kMaxOutputs = DefaultCapacity::outputs;
inline constexpr std::size_t kMaxTerms = DefaultCapacity::terms;
inline constexpr std::size_t kMaxRules = DefaultCapacity::rules;
inline constexpr std::size_t kMaxNameLength = 31;
inline constexpr std::size_t kMaxHedges = 4;  // per proposition

// A NUL-terminated name of at most kMaxNameLength bytes (any bytes but NUL).
using Name = std::array<char, kMaxNameLength + 1>;

// Copies `length` bytes of `text` into `name`; false (name unchanged) when too long.
inline bool set_name(Name& name, const char* text, std::size_t length) noexcept {
  if (length > kMaxNameLength) return false;
  for (std::size_t k = 0; k < length; ++k)
    name[k] = text[k];
  name[length] = '\0';
  return true;
}

template <class Scalar, class Cap = DefaultCapacity>
struct InputSpec {
  Name name{};
  Scalar min = Scalar(0);
  Scalar max = Scalar(1);
  bool lock_range = false;    // clamp the input into [min, max] before fuzzifying
  std::size_t num_terms = 0;  // 0 allowed: an input no rule uses
  std::array<Term<Scalar>, Cap::terms> terms{};
  std::array<Name, Cap::terms> term_names{};
};

enum class OutputTermKind : std::uint8_t {
  Membership,  // a membership function (Mamdani)
  Constant,    // z = coefficients[0]
  Linear,      // z = sum_i coefficients[i] x_i + coefficients[num_inputs]
};

template <class Scalar, class Cap = DefaultCapacity>
struct OutputTerm {
  OutputTermKind kind = OutputTermKind::Membership;
  Term<Scalar> membership{};
  std::array<Scalar, Cap::inputs + 1> coefficients{};
};

template <class Scalar, class Cap = DefaultCapacity>
struct OutputSpec {
  Name name{};
  Scalar min = Scalar(0);
  Scalar max = Scalar(1);
  bool lock_range = false;  // clamp the crisp output into [min, max]
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
  std::size_t num_terms = 0;
  std::array<OutputTerm<Scalar, Cap>, Cap::terms> terms{};
  std::array<Name, Cap::terms> term_names{};
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
};

// "output is [hedges] term".
struct Conclusion {
  std::uint8_t output = 0;
  std::uint8_t term = 0;
  std::uint8_t num_hedges = 0;
  std::array<Hedge, kMaxHedges> hedges{};
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
inline constexpr const char* kActivationNames[] = {"General", "Proportional", "Threshold", "First",
                                                   "Last",    "Highest",      "Lowest"};
inline constexpr const char* kComparisonNames[] = {"<", "<=", "==", "!=", ">=", ">"};

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

// Why a model failed validation: what is wrong, and which input, output or rule (index) it
// concerns.
struct ModelError {
  enum class Where : std::uint8_t { Model, Input, Output, Rule };
  const char* message = nullptr;  // nullptr when valid
  std::size_t index = 0;
  Where where = Where::Model;
  explicit operator bool() const noexcept { return message != nullptr; }
};

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
  bool chained = false;  // some antecedent tests an output (set by add_rule)
  std::array<InputSpec<Scalar, Cap>, Cap::inputs> inputs{};
  std::array<OutputSpec<Scalar, Cap>, Cap::outputs> outputs{};
  std::array<Rule<Scalar>, Cap::rules> rules{};
  std::array<RuleBlock, Cap::blocks> blocks{};
  std::array<Token, Cap::tokens> tokens{};
  std::array<Conclusion, Cap::conclusions> conclusions{};
  std::array<Scalar, 2 * Cap::points> points{};  // (x, y) pairs of the Discrete terms

  // Appends a rule to block `block` from its postfix antecedent and its conclusions; false (model
  // unchanged) when a capacity would be exceeded.
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
      tokens[num_tokens++] = antecedent[k];
    }
    for (std::size_t k = 0; k < n_conclusions; ++k)
      conclusions[num_conclusions++] = then[k];
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

  // Everything evaluate() relies on; the readers check the same things with line numbers first
  // and call this last.
  ModelError validate() const noexcept {
    if (num_inputs < 1 || num_inputs > Cap::inputs) return {"number of inputs out of capacity", 0};
    if (num_outputs < 1 || num_outputs > Cap::outputs)
      return {"number of outputs out of capacity", 0};
    if (num_rules > Cap::rules) return {"more rules than the capacity", 0};
    if (num_blocks < 1 || num_blocks > Cap::blocks)
      return {"number of rule blocks out of capacity", 0};
    if (num_tokens > Cap::tokens || num_conclusions > Cap::conclusions || num_points > Cap::points)
      return {"rule or point storage out of capacity", 0};
    const auto range_ok = [](Scalar lo, Scalar hi) {
      return detail::is_finite(lo) && detail::is_finite(hi) && lo < hi;
    };
    const auto term_ok = [&](const Term<Scalar>& t) {
      if (!t.valid()) return false;
      if (t.shape != Shape::Discrete) return true;
      if (static_cast<std::size_t>(t.first) + t.count > num_points) return false;
      for (std::size_t k = 0; k < t.count; ++k) {
        const Scalar x = points[2 * (t.first + k)];
        const Scalar y = points[2 * (t.first + k) + 1];
        if (!detail::is_finite(x) || !detail::is_finite(y)) return false;
        if (k > 0 && !(points[2 * (t.first + k - 1)] < x)) return false;
      }
      return true;
    };
    for (std::size_t i = 0; i < num_inputs; ++i) {
      const auto& in = inputs[i];
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
    const bool merged = merges_activations();
    for (std::size_t o = 0; o < num_outputs; ++o) {
      const auto& out = outputs[o];
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
      // A weighted defuzzifier over monotonic membership terms is Tsukamoto's method.
      const bool tsukamoto =
          sugeno && out.num_terms > 0 && out.terms[0].kind == OutputTermKind::Membership;
      for (std::size_t t = 0; t < out.num_terms; ++t) {
        const auto& term = out.terms[t];
        const bool membership = term.kind == OutputTermKind::Membership;
        if (membership != tsukamoto && sugeno)
          return {
              "Sugeno defuzzifiers need constant/linear terms (or, for Tsukamoto, monotonic "
              "Ramp, Sigmoid, SShape, ZShape or Concave terms), not a mix",
              o, ModelError::Where::Output};
        if (!sugeno && !membership)
          return {"integral defuzzifiers need membership terms, not constant/linear ones", o,
                  ModelError::Where::Output};
        if (tsukamoto && !is_monotonic(term.membership))
          return {"Tsukamoto terms must be Ramp, Sigmoid, SShape, ZShape or Concave", o,
                  ModelError::Where::Output};
        if (membership && !term_ok(term.membership))
          return {"invalid output term parameters", o, ModelError::Where::Output};
        if (membership && out.exact_centroid && !is_piecewise_linear(term.membership))
          return {"the exact centroid needs piecewise-linear terms of height 1", o,
                  ModelError::Where::Output};
        if (!membership)
          for (std::size_t c = 0; c <= num_inputs; ++c)
            if (!detail::is_finite(term.coefficients[c]))
              return {"non-finite output coefficient", o, ModelError::Where::Output};
      }
    }
    for (std::size_t r = 0; r < num_rules; ++r) {
      const auto& rule = rules[r];
      if (!(rule.weight >= Scalar(0) && rule.weight <= Scalar(1)))
        return {"rule weight must be in [0, 1]", r, ModelError::Where::Rule};
      if (rule.block >= num_blocks) return {"rule of an unknown block", r, ModelError::Where::Rule};
      const RuleBlock& block = blocks[rule.block];
      if (static_cast<std::size_t>(rule.first_token) + rule.num_tokens > num_tokens ||
          rule.num_tokens > Cap::rule_tokens ||
          static_cast<std::size_t>(rule.first_conclusion) + rule.num_conclusions > num_conclusions)
        return {"rule refers to storage it does not own", r, ModelError::Where::Rule};
      std::size_t depth = 0;
      for (std::size_t k = 0; k < rule.num_tokens; ++k) {
        const Token& tok = tokens[rule.first_token + k];
        if (tok.kind == Token::Kind::Proposition) {
          if (tok.input >= num_inputs || tok.num_hedges > kMaxHedges)
            return {"rule names an unknown input", r, ModelError::Where::Rule};
          const bool any = tok.num_hedges > 0 && tok.hedges[tok.num_hedges - 1] == Hedge::Any;
          if (!any && tok.term >= inputs[tok.input].num_terms)
            return {"rule names an unknown input term", r, ModelError::Where::Rule};
          ++depth;
        } else if (tok.kind == Token::Kind::OutputProposition) {
          if (!chained || tok.input >= num_outputs || tok.num_hedges > kMaxHedges)
            return {"rule names an unknown output in its antecedent", r, ModelError::Where::Rule};
          const bool any = tok.num_hedges > 0 && tok.hedges[tok.num_hedges - 1] == Hedge::Any;
          if (!any && tok.term >= outputs[tok.input].num_terms)
            return {"rule names an unknown output term in its antecedent", r,
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
        const Conclusion& c = conclusions[rule.first_conclusion + k];
        if (c.output >= num_outputs || c.term >= outputs[c.output].num_terms ||
            c.num_hedges > kMaxHedges)
          return {"rule names an unknown output term", r, ModelError::Where::Rule};
        for (std::size_t j = 0; j < k; ++j)
          if (conclusions[rule.first_conclusion + j].output == c.output)
            return {"rule concludes twice on one output", r, ModelError::Where::Rule};
        if (!is_sugeno(outputs[c.output].defuzzifier) && !block.has_implication)
          return {"a Mamdani output needs an implication operator in the rule's block", r,
                  ModelError::Where::Rule};
      }
    }
    return {};
  }
};

// Scratch space of one evaluation as pointers and sizes, so that a fixed-size workspace (for
// microcontrollers) and one sized to the loaded model (std::vector, set up once) share the code.
template <class Scalar>
struct WorkspaceView {
  // [num_inputs * stride]: mu of term t of input i at [i * stride + t]
  Scalar* membership = nullptr;
  std::size_t stride = 0;  // >= the largest number of input terms (and of output terms if chained)
  // [num_outputs * stride] (chained models only): degree of term t in output o's fuzzy output
  Scalar* degree = nullptr;
  // [num_outputs]: the last finite value of each output, NaN before any (lock_previous); persists
  // from one evaluation to the next
  Scalar* previous = nullptr;
  Scalar* input = nullptr;         // [num_inputs]: inputs after locking
  Scalar* strength = nullptr;      // [num_rules]: rule firing strengths
  std::uint32_t* order = nullptr;  // [num_rules]: the rules that fire, in firing order
  std::uint32_t* heap = nullptr;   // [num_rules]: Highest/Lowest selection
  Scalar* stack = nullptr;         // [largest number of tokens of a rule]
  Scalar* level = nullptr;         // [largest number of output terms]
  Activation<Scalar>* activations = nullptr;
  std::size_t activations_capacity = 0;  // >= max(num_rules, output terms)
  Scalar* breakpoints = nullptr;         // exact centroid scratch (see defuzzify.hpp)
  Scalar* lines = nullptr;
  Scalar* crossings = nullptr;
  ExactCentroidScratch exact{};

  // True when the view is large enough for `model`.
  template <class Model>
  bool fits(const Model& model) const noexcept {
    bool exact_needed = false;
    for (std::size_t o = 0; o < model.num_outputs; ++o)
      exact_needed = exact_needed || model.outputs[o].exact_centroid;
    const std::size_t acts = detail::max(model.num_rules, model.max_output_terms());
    const std::size_t terms = model.max_output_terms();
    return membership != nullptr && input != nullptr && strength != nullptr && order != nullptr &&
           heap != nullptr && stack != nullptr && level != nullptr && activations != nullptr &&
           previous != nullptr && stride >= model.max_input_terms() &&
           (!model.chained || (degree != nullptr && stride >= terms)) &&
           activations_capacity >= acts &&
           (!exact_needed ||
            (exact.breakpoints_capacity >= 6 * acts + 2 && exact.lines_capacity >= 2 * acts &&
             exact.crossings_capacity >= terms * (terms > 0 ? terms - 1 : 0) / 2));
  }
};

template <class Scalar, std::size_t N>
constexpr std::array<Scalar, N> nan_array() noexcept {
  std::array<Scalar, N> a{};
  for (auto& x : a)
    x = std::numeric_limits<Scalar>::quiet_NaN();
  return a;
}

// The view of a workspace that holds the buffers by the view's names as contiguous containers
// (EngineWorkspace, control::DynamicWorkspace); `stride` as in WorkspaceView.
template <class Workspace>
auto view_of(Workspace& w, std::size_t stride) noexcept
    -> WorkspaceView<typename decltype(Workspace::stack)::value_type> {
  return {w.membership.data(),
          stride,
          w.degree.data(),
          w.previous.data(),
          w.input.data(),
          w.strength.data(),
          w.order.data(),
          w.heap.data(),
          w.stack.data(),
          w.level.data(),
          w.activations.data(),
          w.activations.size(),
          w.breakpoints.data(),
          w.lines.data(),
          w.crossings.data(),
          ExactCentroidScratch{w.breakpoints.size(), w.lines.size(), w.crossings.size()}};
}

// A workspace of fixed size for every model of capacity Cap (no heap; large for DefaultCapacity,
// see docs/rule_files.md).
template <class Scalar, class Cap = DefaultCapacity>
struct EngineWorkspace {
  static constexpr std::size_t kActs = Cap::rules > Cap::terms ? Cap::rules : Cap::terms;
  std::array<Scalar, Cap::inputs * Cap::terms> membership{};
  std::array<Scalar, Cap::outputs * Cap::terms> degree{};
  std::array<Scalar, Cap::outputs> previous = nan_array<Scalar, Cap::outputs>();
  std::array<Scalar, Cap::inputs> input{};
  std::array<Scalar, Cap::rules> strength{};
  std::array<std::uint32_t, Cap::rules> order{};
  std::array<std::uint32_t, Cap::rules> heap{};
  std::array<Scalar, Cap::rule_tokens> stack{};
  std::array<Scalar, Cap::terms> level{};
  std::array<Activation<Scalar>, kActs> activations{};
  std::array<Scalar, 6 * kActs + 2> breakpoints{};
  std::array<Scalar, 2 * kActs> lines{};
  std::array<Scalar, Cap::terms*(Cap::terms - 1) / 2 + 1> crossings{};

  WorkspaceView<Scalar> view() noexcept { return view_of(*this, Cap::terms); }
};

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
template <class Scalar>
Scalar proposition(const WorkspaceView<Scalar>& ws, const Token& tok) noexcept {
  const std::size_t n = tok.num_hedges;
  if (n > 0 && tok.hedges[n - 1] == Hedge::Any)
    return hedge_right_to_left(tok.hedges, n - 1, Scalar(1));
  const Scalar* degrees = tok.kind == Token::Kind::OutputProposition ? ws.degree : ws.membership;
  return hedge_right_to_left(tok.hedges, n, degrees[tok.input * ws.stride + tok.term]);
}

// Weight times the antecedent of rule r (postfix evaluation on ws.stack).
template <class Scalar, class Model>
Scalar rule_strength(const Model& model, const WorkspaceView<Scalar>& ws, std::size_t r) noexcept {
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
      ws.stack[sp++] = proposition(ws, tok);
    }
  }
  return rule.weight * ws.stack[0];
}

// Adds rule r's conclusions to the outputs' term degrees that chained antecedents read
// (fuzzylite's Consequent::modify into Aggregated, then activationDegree).
template <class Scalar, class Model>
void trigger(const Model& model, const WorkspaceView<Scalar>& ws, std::size_t r) noexcept {
  const Rule<Scalar>& rule = model.rules[r];
  Scalar degree = ws.strength[r];
  for (std::size_t k = 0; k < rule.num_conclusions; ++k) {
    const Conclusion& c = model.conclusions[rule.first_conclusion + k];
    degree = hedge_right_to_left(c.hedges, c.num_hedges, degree);
    const auto& out = model.outputs[c.output];
    Scalar& d = ws.degree[c.output * ws.stride + c.term];
    d = out.has_aggregation ? apply(out.aggregation, d, degree) : d + degree;
  }
}

// The crisp value z with mu(z) = w of a monotonic term (fuzzylite's
// WeightedDefuzzifier::tsukamoto, in its operation order).
template <class Scalar>
Scalar tsukamoto(const Term<Scalar>& t, Scalar w, Scalar min, Scalar max,
                 const Scalar* points) noexcept {
  const auto& p = t.p;
  switch (t.shape) {
    case Shape::Ramp:
      return (p[1] - p[0]) / (Scalar(1) - Scalar(0)) * (w - Scalar(0)) + p[0];
    case Shape::Sigmoid:
      if (w == Scalar(1)) return p[1] >= Scalar(0) ? max : min;
      if (w == Scalar(0)) return p[1] >= Scalar(0) ? min : max;
      return p[0] + (std::log(Scalar(1) / w - Scalar(1)) / -p[1]);
    case Shape::SShape:
    case Shape::ZShape: {
      const Scalar difference = p[1] - p[0];
      const Scalar rising = std::sqrt(w * difference * difference / Scalar(2));
      const Scalar falling = std::sqrt(difference * difference * (w - Scalar(1)) / Scalar(-2));
      const bool s = t.shape == Shape::SShape;
      const Scalar a = p[0] + (s ? rising : falling);
      const Scalar b = p[1] + (s ? falling : rising);
      return std::fabs(w - t(a, points)) < std::fabs(w - t(b, points)) ? a : b;
    }
    case Shape::Concave:
      return (p[0] - p[1]) / t(w, points) + Scalar(2) * p[1] - p[0];
    default:
      return t(w, points);
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
template <class Scalar, class Model>
std::size_t activate_block(const Model& model, const WorkspaceView<Scalar>& ws, std::size_t b,
                           std::size_t n) noexcept {
  const Scalar zero = Scalar(0);
  const RuleBlock& block = model.blocks[b];
  const auto in_block = [&](std::size_t r) { return model.rules[r].block == b; };
  const Scalar threshold = static_cast<Scalar>(block.threshold);
  const auto fire = [&](std::size_t r) {
    ws.order[n++] = static_cast<std::uint32_t>(r);
    if (model.chained) trigger(model, ws, r);
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
        const Scalar w = ws.strength[r] = rule_strength(model, ws, r);
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
        if (in_block(r)) sum += ws.strength[r] = rule_strength(model, ws, r);
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
        ws.strength[r] = rule_strength(model, ws, r);
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

}  // namespace engine_detail

// Evaluates `model` at inputs[0 .. num_inputs) into outputs[0 .. num_outputs). The model must
// have passed validate() and `ws` must fit it. Returns NonFiniteInput (outputs 0) for a NaN/inf
// input, NoRuleFired when some output fell back to 0 because no rule fired for it, else Ok.
template <class Scalar, class Cap>
Status evaluate(const EngineModel<Scalar, Cap>& model, const WorkspaceView<Scalar>& ws,
                const Scalar* inputs, Scalar* outputs) noexcept {
  for (std::size_t o = 0; o < model.num_outputs; ++o)
    outputs[o] = Scalar(0);
  for (std::size_t i = 0; i < model.num_inputs; ++i)
    if (!detail::is_finite(inputs[i])) return Status::NonFiniteInput;

  const Scalar* points = model.points.data();
  for (std::size_t i = 0; i < model.num_inputs; ++i) {
    const auto& in = model.inputs[i];
    const Scalar x = in.lock_range ? detail::clamp(inputs[i], in.min, in.max) : inputs[i];
    ws.input[i] = x;
    for (std::size_t t = 0; t < in.num_terms; ++t)
      ws.membership[i * ws.stride + t] = in.terms[t](x, points);
  }

  if (model.chained)
    for (std::size_t k = 0; k < model.num_outputs * ws.stride; ++k)
      ws.degree[k] = Scalar(0);
  std::size_t fired_rules = 0;
  for (std::size_t b = 0; b < model.num_blocks; ++b)
    fired_rules = engine_detail::activate_block(model, ws, b, fired_rules);

  const bool merged = model.merges_activations();
  Status status = Status::Ok;
  for (std::size_t o = 0; o < model.num_outputs; ++o) {
    const OutputSpec<Scalar, Cap>& out = model.outputs[o];
    const bool sugeno = is_sugeno(out.defuzzifier);
    const bool merge = !sugeno && merged && out.aggregation == SNorm::Maximum;
    Scalar y = std::numeric_limits<Scalar>::quiet_NaN();
    bool fired = false;
    Scalar sum = Scalar(0);
    Scalar weights = Scalar(0);
    std::size_t n = 0;
    if (merge)
      for (std::size_t t = 0; t < out.num_terms; ++t)
        ws.level[t] = Scalar(0);
    for (std::size_t f = 0; f < fired_rules; ++f) {
      const std::size_t r = ws.order[f];
      const Rule<Scalar>& rule = model.rules[r];
      Scalar degree = ws.strength[r];
      for (std::size_t k = 0; k < rule.num_conclusions; ++k) {
        const Conclusion& c = model.conclusions[rule.first_conclusion + k];
        degree = engine_detail::hedge_right_to_left(c.hedges, c.num_hedges, degree);
        if (c.output != o) continue;
        fired = true;
        const OutputTerm<Scalar, Cap>& term = out.terms[c.term];
        if (sugeno) {
          Scalar z = term.coefficients[0];
          if (term.kind == OutputTermKind::Membership) {
            z = engine_detail::tsukamoto(term.membership, degree, out.min, out.max, points);
          } else if (term.kind == OutputTermKind::Linear) {
            z = Scalar(0);
            for (std::size_t i = 0; i < model.num_inputs; ++i)
              z += term.coefficients[i] * ws.input[i];
            z += term.coefficients[model.num_inputs];
          }
          sum += degree * z;
          weights += degree;
        } else if (merge) {
          ws.level[c.term] = detail::max(ws.level[c.term], degree);
        } else {
          ws.activations[n++] = {&term.membership, degree, model.blocks[rule.block].implication};
        }
      }
    }
    if (fired && sugeno) {
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
      status = Status::NoRuleFired;
    }
    outputs[o] = y;
  }
  return status;
}

// A model with its own fixed-size workspace. Large for DefaultCapacity (docs/rule_files.md):
// create it once, e.g. on the heap at start-up.
template <class Scalar, class Cap = DefaultCapacity>
class Engine {
 public:
  using Model = EngineModel<Scalar, Cap>;

  Engine() noexcept = default;
  // An invalid model leaves the engine unconfigured: evaluate() returns InvalidConfig.
  explicit Engine(const Model& model) noexcept { (void)set_model(model); }

  // Also forgets the previous outputs (lock_previous).
  ModelError set_model(const Model& model) noexcept {
    const ModelError error = model.validate();
    if (!error) model_ = model;
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
  const EngineWorkspace<Scalar, Cap>& workspace() const noexcept { return ws_; }

 private:
  Model model_{};
  EngineWorkspace<Scalar, Cap> ws_{};
  bool configured_ = false;
};

}  // namespace fuzzypid::fuzzy
