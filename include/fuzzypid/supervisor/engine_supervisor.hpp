// A loaded rule base (fuzzy::EngineModel) as a supervisor of FuzzyPid (the concept of
// supervisor/supervisor.hpp): two inputs and three outputs, bound by name whatever their order in
// the file -- the inputs named `e` (the scaled error) and `ec` (the scaled error rate), the
// outputs `dKp`, `dKi` and `dKd` (the gain corrections), as `fuzzypid export-rules` writes them.
// A model with other names (or counts) is not a valid supervisor; supervisor_binding_error()
// says which names it has and which it needs.
//
// The model is immutable and shared by every joint; the supervisor keeps a non-owning pointer to
// it, so the model must outlive the supervisor and every controller using it. Per-joint scratch
// is a Workspace sized to the loaded model (make_workspace() allocates once, at set-up; infer()
// never allocates).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzzypid/fuzzy/engine.hpp"
#include "fuzzypid/fuzzy/engine_model_validation.hpp"
#include "fuzzypid/fuzzy/engine_workspace.hpp"
#include "fuzzypid/status.hpp"

namespace fuzzypid::supervisor {

// The names a supervisor's rule file must give its inputs and outputs (exact, case-sensitive).
inline constexpr const char* kSupervisorInputNames[2] = {"e", "ec"};
inline constexpr const char* kSupervisorOutputNames[3] = {"dKp", "dKi", "dKd"};

namespace supervisor_detail {
inline bool name_is(const fuzzy::Name& name, const char* want) noexcept {
  std::size_t k = 0;
  for (; want[k] != '\0'; ++k)
    if (k >= name.size() || name[k] != want[k]) return false;
  return k < name.size() && name[k] == '\0';
}

// The index of the variable named `want` among `vars[0 .. n)`, or -1 when none or several are.
template <class Vars>
int index_named(const Vars& vars, std::size_t n, const char* want) noexcept {
  int found = -1;
  for (std::size_t k = 0; k < n; ++k)
    if (name_is(vars[k].name, want)) {
      if (found >= 0) return -1;
      found = static_cast<int>(k);
    }
  return found;
}
}  // namespace supervisor_detail

// Empty when `model` binds as a supervisor (2 inputs named e and ec, 3 outputs named dKp, dKi and
// dKd, in any order); otherwise the names it has and the names it needs. Set-up only (allocates).
template <class Scalar, class Cap>
std::string supervisor_binding_error(const fuzzy::EngineModel<Scalar, Cap>& model) {
  bool ok = model.num_inputs == 2 && model.num_outputs == 3;
  for (std::size_t k = 0; ok && k < 2; ++k)
    ok = supervisor_detail::index_named(model.inputs, model.num_inputs, kSupervisorInputNames[k]) >=
         0;
  for (std::size_t k = 0; ok && k < 3; ++k)
    ok = supervisor_detail::index_named(model.outputs, model.num_outputs,
                                        kSupervisorOutputNames[k]) >= 0;
  if (ok) return {};
  const auto list = [](const auto& vars, std::size_t n) {
    std::string s = "(";
    for (std::size_t k = 0; k < n; ++k) {
      if (k > 0) s += ", ";
      s += vars[k].name.data();
    }
    return s + ")";
  };
  return "the file has inputs " + list(model.inputs, model.num_inputs) + " and outputs " +
         list(model.outputs, model.num_outputs) +
         "; a supervisor needs inputs (e, ec) and outputs (dKp, dKi, dKd), each name once, in "
         "any order";
}

template <class Scalar, class Cap = fuzzy::DefaultCapacity>
class EngineSupervisor {
 public:
  using Model = fuzzy::EngineModel<Scalar, Cap>;
  using Workspace = fuzzy::DynamicWorkspace<Scalar>;

  EngineSupervisor() noexcept = default;
  // `model` must outlive the supervisor and its controllers.
  explicit EngineSupervisor(const Model* model) noexcept : model_(model) {
    if (model == nullptr || model->num_inputs != 2 || model->num_outputs != 3 ||
        fuzzy::validate(*model))
      return;
    // NOLINTNEXTLINE(modernize-loop-convert): k indexes the names and the binding alike
    for (std::size_t k = 0; k < 2; ++k) {
      const int i = supervisor_detail::index_named(model->inputs, 2, kSupervisorInputNames[k]);
      if (i < 0) return;
      input_of_[k] = static_cast<std::uint8_t>(i);
    }
    // NOLINTNEXTLINE(modernize-loop-convert): g indexes the names and the binding alike
    for (std::size_t g = 0; g < 3; ++g) {
      const int o = supervisor_detail::index_named(model->outputs, 3, kSupervisorOutputNames[g]);
      if (o < 0) return;
      output_of_[g] = static_cast<std::uint8_t>(o);
    }
    valid_ = true;
  }

  // True when the model is present, valid and has the 2 inputs and 3 outputs FuzzyPid needs,
  // named as above.
  bool valid() const noexcept { return valid_; }

  // Set-up: a workspace sized to the model (allocates).
  Workspace make_workspace() const { return valid_ ? Workspace(*model_) : Workspace(); }

  // One inference: delta = (dKp, dKi, dKd). Ok, NoRuleFired (delta = 0) or a fault
  // (InvalidConfig for an invalid supervisor or a workspace not made for this model).
  [[nodiscard]] Status infer(Scalar e, Scalar ec, Workspace& ws,
                             std::array<Scalar, 3>& delta) const noexcept {
    delta = {};
    if (!valid_ || !ws.view().fits(*model_)) return Status::InvalidConfig;
    Scalar in[2] = {};
    in[input_of_[0]] = e;
    in[input_of_[1]] = ec;
    Scalar out[3] = {};
    const Status s = fuzzy::evaluate(*model_, ws.view(), in, out);
    for (std::size_t g = 0; g < 3; ++g)
      delta[g] = out[output_of_[g]];
    return s;
  }

 private:
  const Model* model_ = nullptr;
  bool valid_ = false;
  std::array<std::uint8_t, 2> input_of_{};   // the model's index of e, ec
  std::array<std::uint8_t, 3> output_of_{};  // the model's index of dKp, dKi, dKd
};

}  // namespace fuzzypid::supervisor
