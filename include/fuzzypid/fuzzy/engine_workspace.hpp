// The scratch space of one evaluation of an engine model (fuzzy/engine.hpp): fuzzified inputs,
// rule strengths, the fired rules in order, activations, exact-centroid scratch, the degrees of
// the outputs' terms that chained antecedents read, and each output's previous value
// (lock-previous), which persists from one evaluation to the next.
//
// WorkspaceView holds it as pointers and sizes, so one evaluation code serves EngineWorkspace
// (fixed size for every model of a capacity, no heap: microcontrollers) and DynamicWorkspace
// (sized to one loaded model; its construction allocates, evaluation does not).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "fuzzypid/fuzzy/defuzzify.hpp"
#include "fuzzypid/fuzzy/engine_model.hpp"

namespace fuzzypid::fuzzy {

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
// (EngineWorkspace, supervisor::DynamicWorkspace); `stride` as in WorkspaceView.
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

// A workspace sized to one model (set-up allocates; evaluation does not).
template <class Scalar>
struct DynamicWorkspace {
  std::vector<Scalar> membership, degree, previous, input, strength, stack, level, breakpoints,
      lines, crossings;
  std::vector<Activation<Scalar>> activations;
  std::vector<std::uint32_t> order, heap;
  std::size_t stride = 0;

  DynamicWorkspace() = default;
  template <class Model>
  explicit DynamicWorkspace(const Model& model) {
    const std::size_t terms = model.max_output_terms();
    stride = detail::max<std::size_t>(1, model.max_input_terms());
    if (model.chained) stride = detail::max(stride, terms);
    const std::size_t acts = detail::max<std::size_t>(1, detail::max(model.num_rules, terms));
    bool exact = false;
    for (std::size_t o = 0; o < model.num_outputs; ++o)
      exact = exact || model.outputs[o].exact_centroid;
    membership.assign(detail::max<std::size_t>(1, model.num_inputs) * stride, Scalar(0));
    if (model.chained) degree.assign(model.num_outputs * stride, Scalar(0));
    previous.assign(detail::max<std::size_t>(1, model.num_outputs),
                    std::numeric_limits<Scalar>::quiet_NaN());
    input.assign(detail::max<std::size_t>(1, model.num_inputs), Scalar(0));
    strength.assign(detail::max<std::size_t>(1, model.num_rules), Scalar(0));
    order.assign(detail::max<std::size_t>(1, model.num_rules), 0);
    heap.assign(detail::max<std::size_t>(1, model.num_rules), 0);
    stack.assign(detail::max<std::size_t>(1, model.max_rule_tokens()), Scalar(0));
    level.assign(detail::max<std::size_t>(1, terms), Scalar(0));
    activations.assign(acts, Activation<Scalar>{});
    if (exact) {
      breakpoints.assign(6 * acts + 2, Scalar(0));
      lines.assign(2 * acts, Scalar(0));
      crossings.assign(terms * (terms > 0 ? terms - 1 : 0) / 2 + 1, Scalar(0));
    }
  }

  WorkspaceView<Scalar> view() noexcept { return view_of(*this, stride); }
};

}  // namespace fuzzypid::fuzzy
