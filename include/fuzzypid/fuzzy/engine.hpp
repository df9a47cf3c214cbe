// A run-time-sized fuzzy inference engine with a capacity fixed at compile time: the form a rule
// base loaded from a MATLAB .fis or fuzzylite .fll file takes (see fuzzypid/io/rule_file.hpp and
// docs/rule_files.md).
//
// Capacity (kMax* below): 8 inputs, 8 outputs, 16 terms per variable, 512 rules, names of up to
// 31 bytes. A rule holds at most one proposition per input (MATLAB's rule model), so it has at
// most 8 antecedents, joined all by AND or all by OR, and concludes on any subset of the outputs.
//
// Per evaluation:
//   mu_it         = term t of input i at x_i (x_i clamped to the range if lock_range)
//   rule strength = weight * AND/OR-fold of the antecedents in input order (NOT: 1 - mu)
//   Mamdani output (integral defuzzifier): activations (term, strength) of the rules concluding on
//     it, shaped by the implication and aggregated (defuzzify.hpp); Maximum keeps one activation
//     per term (its largest strength, exact because min/prod are monotone), Sum one per rule;
//     then centroid (sampled or exact), bisector, mean/smallest/largest of maximum.
//   Sugeno output (constant/linear terms): z_r = c or sum_i c_i x_i + c_0 per firing rule;
//     weighted average sum(w_r z_r) / sum(w_r) or weighted sum sum(w_r z_r).
// The semantics are fuzzylite 6's (its tolerance macheps set to 0), which agree with MATLAB's
// for everything here except the sampling of the integral defuzzifiers (see the docs).
//
// The model is plain data; evaluation writes only into a separate workspace, is noexcept and
// allocates nothing. An output whose aggregated set is empty takes the output's default value,
// or 0 with Status::NoRuleFired when the default is NaN (fuzzylite's "default: nan").
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "fuzzypid/fuzzy/defuzzify.hpp"
#include "fuzzypid/fuzzy/membership.hpp"
#include "fuzzypid/scalar.hpp"
#include "fuzzypid/status.hpp"

namespace fuzzypid::fuzzy {

inline constexpr std::size_t kMaxInputs = 8;
inline constexpr std::size_t kMaxOutputs = 8;
inline constexpr std::size_t kMaxTerms = 16;
inline constexpr std::size_t kMaxRules = 512;
inline constexpr std::size_t kMaxNameLength = 31;

// A NUL-terminated name of at most kMaxNameLength bytes.
using Name = std::array<char, kMaxNameLength + 1>;

// Copies `length` bytes of `text` into `name`; false (name unchanged) when too long.
inline bool set_name(Name& name, const char* text, std::size_t length) noexcept {
  if (length > kMaxNameLength) return false;
  for (std::size_t k = 0; k < length; ++k)
    name[k] = text[k];
  name[length] = '\0';
  return true;
}

enum class TNorm : std::uint8_t { None, Minimum, Product };
enum class SNorm : std::uint8_t { None, Maximum, ProbabilisticSum };

enum class Defuzzifier : std::uint8_t {
  Centroid,           // integral; sampled, or exact for piecewise-linear terms
  Bisector,           // integral, sampled
  MeanOfMaximum,      // integral, sampled
  SmallestOfMaximum,  // integral, sampled
  LargestOfMaximum,   // integral, sampled
  WeightedAverage,    // Sugeno
  WeightedSum,        // Sugeno
};

constexpr bool is_sugeno(Defuzzifier d) noexcept {
  return d == Defuzzifier::WeightedAverage || d == Defuzzifier::WeightedSum;
}

template <class Scalar>
constexpr Scalar apply(TNorm op, Scalar a, Scalar b) noexcept {
  return op == TNorm::Minimum ? detail::min(a, b) : a * b;
}
template <class Scalar>
constexpr Scalar apply(SNorm op, Scalar a, Scalar b) noexcept {
  return op == SNorm::Maximum ? detail::max(a, b) : a + b - a * b;
}

template <class Scalar>
struct InputSpec {
  Name name{};
  Scalar min = Scalar(0);
  Scalar max = Scalar(1);
  bool lock_range = false;  // clamp the input into [min, max] before fuzzifying
  std::size_t num_terms = 0;
  std::array<Term<Scalar>, kMaxTerms> terms{};
  std::array<Name, kMaxTerms> term_names{};
};

enum class OutputTermKind : std::uint8_t {
  Membership,  // a membership function (Mamdani)
  Constant,    // z = coefficients[0]
  Linear,      // z = sum_i coefficients[i] x_i + coefficients[num_inputs]
};

template <class Scalar>
struct OutputTerm {
  OutputTermKind kind = OutputTermKind::Membership;
  Term<Scalar> membership{};
  std::array<Scalar, kMaxInputs + 1> coefficients{};
};

template <class Scalar>
struct OutputSpec {
  Name name{};
  Scalar min = Scalar(0);
  Scalar max = Scalar(1);
  bool lock_range = false;  // clamp the crisp output into [min, max]
  Scalar default_value = std::numeric_limits<Scalar>::quiet_NaN();  // when no rule fired
  Defuzzifier defuzzifier = Defuzzifier::Centroid;
  int resolution = 100;         // samples of the integral defuzzifiers
  bool exact_centroid = false;  // Centroid in closed form instead of sampled
  Aggregation aggregation = Aggregation::Maximum;
  std::size_t num_terms = 0;
  std::array<OutputTerm<Scalar>, kMaxTerms> terms{};
  std::array<Name, kMaxTerms> term_names{};
};

template <class Scalar>
struct Rule {
  // antecedent[i]: 0 = input i not used, k > 0 = "is term k-1", k < 0 = "is not term -k-1".
  std::array<std::int8_t, kMaxInputs> antecedent{};
  // consequent[o]: 0 = output o not concluded, k > 0 = "is term k-1".
  std::array<std::int8_t, kMaxOutputs> consequent{};
  Scalar weight = Scalar(1);
  bool disjunction = false;  // antecedents joined by OR instead of AND
};

// Why a model failed validation (index = the variable, term or rule concerned).
struct ModelError {
  const char* message = nullptr;  // nullptr when valid
  std::size_t index = 0;
  explicit operator bool() const noexcept { return message != nullptr; }
};

template <class Scalar>
struct EngineModel {
  FUZZYPID_ASSERT_SCALAR(Scalar);

  Name name{};
  std::size_t num_inputs = 0;
  std::size_t num_outputs = 0;
  std::size_t num_rules = 0;
  std::array<InputSpec<Scalar>, kMaxInputs> inputs{};
  std::array<OutputSpec<Scalar>, kMaxOutputs> outputs{};
  std::array<Rule<Scalar>, kMaxRules> rules{};
  TNorm conjunction = TNorm::Minimum;
  SNorm disjunction = SNorm::Maximum;
  TNorm implication = TNorm::Minimum;  // Mamdani outputs only

  // Everything evaluate() relies on; the importers check the same things with line numbers.
  ModelError validate() const noexcept {
    if (num_inputs < 1 || num_inputs > kMaxInputs) return {"number of inputs out of 1..8", 0};
    if (num_outputs < 1 || num_outputs > kMaxOutputs) return {"number of outputs out of 1..8", 0};
    if (num_rules > kMaxRules) return {"more than 512 rules", 0};
    const auto range_ok = [](Scalar lo, Scalar hi) {
      return detail::is_finite(lo) && detail::is_finite(hi) && lo < hi;
    };
    for (std::size_t i = 0; i < num_inputs; ++i) {
      const auto& in = inputs[i];
      if (!range_ok(in.min, in.max)) return {"input range must be finite with min < max", i};
      if (in.num_terms < 1 || in.num_terms > kMaxTerms) return {"input terms out of 1..16", i};
      for (std::size_t t = 0; t < in.num_terms; ++t)
        if (!in.terms[t].valid()) return {"invalid input term parameters", i};
    }
    for (std::size_t o = 0; o < num_outputs; ++o) {
      const auto& out = outputs[o];
      if (!range_ok(out.min, out.max)) return {"output range must be finite with min < max", o};
      if (out.num_terms < 1 || out.num_terms > kMaxTerms) return {"output terms out of 1..16", o};
      if (!is_sugeno(out.defuzzifier) && out.resolution < 1) return {"resolution must be >= 1", o};
      if (!is_sugeno(out.defuzzifier) && implication == TNorm::None)
        return {"a Mamdani output needs an implication operator", o};
      if (out.default_value == out.default_value && !detail::is_finite(out.default_value))
        return {"default value must be finite or NaN", o};
      for (std::size_t t = 0; t < out.num_terms; ++t) {
        const auto& term = out.terms[t];
        const bool membership = term.kind == OutputTermKind::Membership;
        if (membership == is_sugeno(out.defuzzifier))
          return {"Sugeno defuzzifiers need constant/linear terms, the others membership terms", o};
        if (membership && !term.membership.valid()) return {"invalid output term parameters", o};
        if (membership && out.defuzzifier == Defuzzifier::Centroid && out.exact_centroid &&
            !is_piecewise_linear(term.membership))
          return {"the exact centroid needs piecewise-linear terms", o};
        if (!membership)
          for (std::size_t c = 0; c <= num_inputs; ++c)
            if (!detail::is_finite(term.coefficients[c]))
              return {"non-finite output coefficient", o};
      }
    }
    for (std::size_t r = 0; r < num_rules; ++r) {
      const auto& rule = rules[r];
      if (!(rule.weight >= Scalar(0) && rule.weight <= Scalar(1)))
        return {"rule weight must be in [0, 1]", r};
      std::size_t antecedents = 0;
      for (std::size_t i = 0; i < kMaxInputs; ++i) {
        const int a = rule.antecedent[i];
        if (a == 0) continue;
        const int t = a > 0 ? a : -a;
        if (i >= num_inputs || t > static_cast<int>(inputs[i].num_terms))
          return {"rule names an unknown input term", r};
        ++antecedents;
      }
      if (antecedents == 0) return {"rule has no antecedent", r};
      if (antecedents > 1 &&
          (rule.disjunction ? disjunction == SNorm::None : conjunction == TNorm::None))
        return {"rule needs a conjunction/disjunction operator that is none", r};
      std::size_t consequents = 0;
      for (std::size_t o = 0; o < kMaxOutputs; ++o) {
        const int c = rule.consequent[o];
        if (c == 0) continue;
        if (o >= num_outputs || c < 0 || c > static_cast<int>(outputs[o].num_terms))
          return {"rule names an unknown output term", r};
        ++consequents;
      }
      if (consequents == 0) return {"rule has no consequent", r};
    }
    return {};
  }
};

// Scratch space of one evaluation, and what can be read back after it.
template <class Scalar>
struct EngineWorkspace {
  std::array<std::array<Scalar, kMaxTerms>, kMaxInputs> membership{};  // mu[i][t] at the input
  std::array<Scalar, kMaxInputs> input{};                              // inputs after locking
  std::array<Scalar, kMaxRules> strength{};                            // rule firing strengths
  std::array<Activation<Scalar>, kMaxRules> activations{};
  std::array<Scalar, 6 * kMaxRules + 2> breakpoints{};
  std::array<Scalar, 2 * kMaxRules> lines{};
  std::array<Scalar, kMaxTerms*(kMaxTerms - 1) / 2> crossings{};
};

// Evaluates `model` at inputs[0 .. num_inputs) into outputs[0 .. num_outputs). The model must
// have passed validate(). Returns NonFiniteInput (outputs 0) for a NaN/inf input, NoRuleFired
// when some output fell back to 0 because no rule fired for it, else Ok.
template <class Scalar>
Status evaluate(const EngineModel<Scalar>& model, EngineWorkspace<Scalar>& ws, const Scalar* inputs,
                Scalar* outputs) noexcept {
  for (std::size_t o = 0; o < model.num_outputs; ++o)
    outputs[o] = Scalar(0);
  for (std::size_t i = 0; i < model.num_inputs; ++i)
    if (!detail::is_finite(inputs[i])) return Status::NonFiniteInput;

  for (std::size_t i = 0; i < model.num_inputs; ++i) {
    const auto& in = model.inputs[i];
    const Scalar x = in.lock_range ? detail::clamp(inputs[i], in.min, in.max) : inputs[i];
    ws.input[i] = x;
    for (std::size_t t = 0; t < in.num_terms; ++t)
      ws.membership[i][t] = in.terms[t](x);
  }

  for (std::size_t r = 0; r < model.num_rules; ++r) {
    const Rule<Scalar>& rule = model.rules[r];
    bool first = true;
    Scalar degree = Scalar(0);
    for (std::size_t i = 0; i < model.num_inputs; ++i) {
      const int a = rule.antecedent[i];
      if (a == 0) continue;
      const Scalar mu = a > 0 ? ws.membership[i][static_cast<std::size_t>(a - 1)]
                              : Scalar(1) - ws.membership[i][static_cast<std::size_t>(-a - 1)];
      if (first) {
        degree = mu;
        first = false;
      } else {
        degree = rule.disjunction ? apply(model.disjunction, degree, mu)
                                  : apply(model.conjunction, degree, mu);
      }
    }
    ws.strength[r] = rule.weight * degree;
  }

  Status status = Status::Ok;
  for (std::size_t o = 0; o < model.num_outputs; ++o) {
    const OutputSpec<Scalar>& out = model.outputs[o];
    Scalar y = std::numeric_limits<Scalar>::quiet_NaN();
    bool fired = false;
    if (is_sugeno(out.defuzzifier)) {
      Scalar sum = Scalar(0);
      Scalar weights = Scalar(0);
      for (std::size_t r = 0; r < model.num_rules; ++r) {
        const int c = model.rules[r].consequent[o];
        const Scalar w = ws.strength[r];
        if (c == 0 || !(w > Scalar(0))) continue;
        const OutputTerm<Scalar>& term = out.terms[static_cast<std::size_t>(c - 1)];
        Scalar z = term.coefficients[0];
        if (term.kind == OutputTermKind::Linear) {
          z = Scalar(0);
          for (std::size_t i = 0; i < model.num_inputs; ++i)
            z += term.coefficients[i] * ws.input[i];
          z += term.coefficients[model.num_inputs];
        }
        sum += w * z;
        weights += w;
        fired = true;
      }
      if (fired) y = out.defuzzifier == Defuzzifier::WeightedAverage ? sum / weights : sum;
    } else {
      std::size_t n = 0;
      if (out.aggregation == Aggregation::Maximum) {
        std::array<Scalar, kMaxTerms> level{};
        for (std::size_t r = 0; r < model.num_rules; ++r) {
          const int c = model.rules[r].consequent[o];
          if (c != 0) {
            Scalar& l = level[static_cast<std::size_t>(c - 1)];
            l = detail::max(l, ws.strength[r]);
          }
        }
        for (std::size_t t = 0; t < out.num_terms; ++t)
          if (level[t] > Scalar(0)) ws.activations[n++] = {&out.terms[t].membership, level[t]};
      } else {
        for (std::size_t r = 0; r < model.num_rules; ++r) {
          const int c = model.rules[r].consequent[o];
          if (c != 0 && ws.strength[r] > Scalar(0))
            ws.activations[n++] = {&out.terms[static_cast<std::size_t>(c - 1)].membership,
                                   ws.strength[r]};
        }
      }
      fired = n > 0;
      if (fired) {
        const AggregatedSet<Scalar> set{
            ws.activations.data(), n,
            model.implication == TNorm::Minimum ? Implication::Minimum : Implication::Product,
            out.aggregation};
        switch (out.defuzzifier) {
          case Defuzzifier::Centroid:
            y = out.exact_centroid
                    ? centroid_exact(set, out.min, out.max, ws.breakpoints.data(), ws.lines.data(),
                                     ws.crossings.data(),
                                     {ws.breakpoints.size(), ws.lines.size(), ws.crossings.size()})
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
    }
    if (!fired) y = out.default_value;
    if (y != y) {
      y = Scalar(0);
      status = Status::NoRuleFired;
    } else if (out.lock_range) {
      y = detail::clamp(y, out.min, out.max);
    }
    outputs[o] = y;
  }
  return status;
}

// A model with its own workspace. Large (~93 kB for double): create it once, e.g. on the heap at
// start-up.
template <class Scalar>
class Engine {
 public:
  using Model = EngineModel<Scalar>;

  Engine() noexcept = default;
  // An invalid model leaves the engine unconfigured: evaluate() returns InvalidConfig.
  explicit Engine(const Model& model) noexcept { (void)set_model(model); }

  ModelError set_model(const Model& model) noexcept {
    const ModelError error = model.validate();
    if (!error) model_ = model;
    configured_ = !error;
    return error;
  }

  // Writes num_outputs() values; see fuzzy::evaluate.
  Status evaluate(const Scalar* inputs, Scalar* outputs) noexcept {
    if (!configured_) return Status::InvalidConfig;
    return fuzzy::evaluate(model_, ws_, inputs, outputs);
  }

  const Model& model() const noexcept { return model_; }
  std::size_t num_inputs() const noexcept { return model_.num_inputs; }
  std::size_t num_outputs() const noexcept { return model_.num_outputs; }
  // Firing strength of rule r in the last evaluation (weight included).
  Scalar rule_strength(std::size_t r) const noexcept { return ws_.strength[r]; }
  const EngineWorkspace<Scalar>& workspace() const noexcept { return ws_; }

 private:
  Model model_{};
  EngineWorkspace<Scalar> ws_{};
  bool configured_ = false;
};

// The result FuzzyPid expects from its supervisor: outputs (dKp, dKi, dKd) and a status.
template <class Scalar>
struct SupervisorResult {
  std::array<Scalar, 3> output{};
  Status status = Status::Ok;
};

// Adapts a loaded model with two inputs (e, ec, in this order) and three outputs (dKp, dKi, dKd)
// to control::FuzzyPid's System interface. It refers to the model (which must outlive it) and
// owns a workspace, so it is not thread-safe: give each controller its own.
template <class Scalar>
class EngineSupervisor {
 public:
  using Result = SupervisorResult<Scalar>;

  EngineSupervisor() noexcept = default;
  explicit EngineSupervisor(const EngineModel<Scalar>* model) noexcept
      : model_(model),
        valid_(model != nullptr && model->num_inputs == 2 && model->num_outputs == 3 &&
               !model->validate()) {}

  // True when the model is present, valid and has the 2 inputs and 3 outputs FuzzyPid needs.
  bool valid() const noexcept { return valid_; }

  // The supervisor concept of control/supervisor.hpp: the caller's workspace instead of ws_.
  using Workspace = EngineWorkspace<Scalar>;
  Workspace make_workspace() const noexcept { return {}; }
  [[nodiscard]] Status infer(Scalar e, Scalar ec, Workspace& ws,
                             std::array<Scalar, 3>& delta) const noexcept {
    delta = {};
    if (!valid_) return Status::InvalidConfig;
    const Scalar in[2] = {e, ec};
    return fuzzy::evaluate(*model_, ws, in, delta.data());
  }

  Result infer(Scalar e, Scalar ec) const noexcept {
    Result r;
    if (!valid_) {
      r.status = Status::InvalidConfig;
      return r;
    }
    const Scalar in[2] = {e, ec};
    r.status = fuzzy::evaluate(*model_, ws_, in, r.output.data());
    return r;
  }

 private:
  const EngineModel<Scalar>* model_ = nullptr;
  bool valid_ = false;
  mutable EngineWorkspace<Scalar> ws_{};
};

}  // namespace fuzzypid::fuzzy
