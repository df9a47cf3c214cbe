// A loaded rule base (fuzzy::EngineModel) as a supervisor of FuzzyPid (the concept of
// control/supervisor.hpp): two inputs (e, ec, in this order) and three outputs (dKp, dKi, dKd).
//
// The model is immutable and shared by every joint; the supervisor keeps a non-owning pointer to
// it, so the model must outlive the supervisor and every controller using it. Per-joint scratch
// is a Workspace sized to the loaded model (make_workspace() allocates once, at set-up; infer()
// never allocates).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "fuzzypid/fuzzy/engine.hpp"
#include "fuzzypid/status.hpp"

namespace fuzzypid::fuzzy {

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

namespace fuzzypid::control {

template <class Scalar, class Cap = fuzzy::DefaultCapacity>
class EngineSupervisor {
 public:
  using Model = fuzzy::EngineModel<Scalar, Cap>;
  using Workspace = fuzzy::DynamicWorkspace<Scalar>;

  EngineSupervisor() noexcept = default;
  // `model` must outlive the supervisor and its controllers.
  explicit EngineSupervisor(const Model* model)
      : model_(model),
        valid_(model != nullptr && model->num_inputs == 2 && model->num_outputs == 3 &&
               !model->validate()) {}

  // True when the model is present, valid and has the 2 inputs and 3 outputs FuzzyPid needs.
  bool valid() const noexcept { return valid_; }

  // Set-up: a workspace sized to the model (allocates).
  Workspace make_workspace() const { return valid_ ? Workspace(*model_) : Workspace(); }

  // One inference: delta = (dKp, dKi, dKd). Ok, NoRuleFired (delta = 0) or a fault
  // (InvalidConfig for an invalid supervisor or a workspace not made for this model).
  [[nodiscard]] Status infer(Scalar e, Scalar ec, Workspace& ws,
                             std::array<Scalar, 3>& delta) const noexcept {
    delta = {};
    if (!valid_ || !ws.view().fits(*model_)) return Status::InvalidConfig;
    const Scalar in[2] = {e, ec};
    return fuzzy::evaluate(*model_, ws.view(), in, delta.data());
  }

 private:
  const Model* model_ = nullptr;
  bool valid_ = false;
};

}  // namespace fuzzypid::control
