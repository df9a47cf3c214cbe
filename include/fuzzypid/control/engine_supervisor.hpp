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

#include "fuzzypid/fuzzy/engine.hpp"
#include "fuzzypid/fuzzy/engine_workspace.hpp"
#include "fuzzypid/status.hpp"

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
