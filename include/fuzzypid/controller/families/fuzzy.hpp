// The fuzzy family: K = K0 + S dK(Ke e, Kec ec) (Eq. 6), dK from the paper's Tables 2-4
// (paper::System) or from a .fis/.fll/.fcl rule file (supervisor::EngineSupervisor).
#pragma once

#include <memory>
#include <string>

#include "fuzzypid/controller/controller_spec.hpp"
#include "fuzzypid/controller/family.hpp"
#include "fuzzypid/controller/runtime.hpp"
#include "fuzzypid/paper.hpp"
#include "fuzzypid/supervisor/engine_supervisor.hpp"

namespace fuzzypid::controller::families {

struct Fuzzy {
  static constexpr FamilyTraits kTraits{
      "fuzzy",
      "K = K0 + S dK(Ke e, Kec ec): the paper's Tables 2-4 (Eq. 6) or a .fis/.fll/.fcl rule file",
      OutputScale::Scales, true, false};
  using Tables = SupervisedJoints<paper::System<double>>;
  using RuleFile = SupervisedJoints<supervisor::EngineSupervisor<double>>;
  using Runtimes = std::tuple<Tables, RuleFile>;

  [[nodiscard]] static std::string validate(const ControllerSpec& /*spec*/) { return {}; }

  // dK is in the file's units: S converts like the gains themselves.
  static void configure(const ControllerSpec& spec,
                        supervisor::FuzzyPidConfig<double>& config) noexcept {
    const pid::Gains<double> unit =
        to_continuous({1.0, 1.0, 1.0}, spec.units.form, spec.units.tick_s);
    const auto& s = spec.supervisor.output_scale;
    config.output_scale = {s[0] * unit.kp, s[1] * unit.ki, s[2] * unit.kd};
    config.gain_update = spec.supervisor.gain_update;
  }

  // The header export of the supervisor (family.hpp, SupervisorCode). `code` writes what this
  // file cannot: code.literal(v), an exact literal of v as Scalar, and code.rule_base(model,
  // file), a rule file's model and its supervisor.
  template <class Code>
  [[nodiscard]] static SupervisorCode header_code(const ControllerSpec& spec, const Code& code) {
    const SupervisorSpec& sup = spec.supervisor;
    if (sup.rule_model != nullptr)
      return {
          "#include <array>\n\n#include \"fuzzypid/supervisor/fuzzy_pid.hpp\"\n"
          "#include \"fuzzypid/fuzzy/engine.hpp\"\n",
          code.rule_base(*sup.rule_model, sup.rule_file)};
    return {"#include \"fuzzypid/supervisor/fuzzy_pid.hpp\"\n#include \"fuzzypid/paper.hpp\"\n",
            std::string("template <class Scalar>\nusing Supervisor = "
                        "fuzzypid::paper::System<Scalar>;\n\n"
                        "// The shared, immutable supervisor the joints point to.\n"
                        "template <class Scalar>\ninline constexpr Supervisor<Scalar> "
                        "kSupervisor =\n"
                        "    fuzzypid::paper::make_system<Scalar>(fuzzypid::fuzzy::Conjunction::") +
                (sup.conjunction == fuzzy::Conjunction::Minimum ? "Minimum" : "Product") +
                ", fuzzypid::paper::Tables::" +
                (sup.rule_base == paper::Tables::Corrected ? "Corrected" : "Printed") + ");\n\n"};
  }

  template <class Runtime>
  [[nodiscard]] static bool build(const ControllerSpec& spec, const JointConfigs& configs,
                                  Runtime& out, std::string& error) {
    const auto& model = spec.supervisor.rule_model;
    if (model == nullptr) {
      auto tables = std::make_unique<const paper::System<double>>(
          paper::make_system<double>(spec.supervisor.conjunction, spec.supervisor.rule_base));
      return make_supervised_joints(std::move(tables), configs, "fuzzy PID",
                                    out.template emplace<Tables>(), error);
    }
    // A rule file: the engine supervisor on the loaded model (both shared by the joints).
    auto engine = std::make_unique<const supervisor::EngineSupervisor<double>>(model.get());
    if (!engine->valid()) {
      error = "the rule file's model is not a valid supervisor (2 inputs, 3 outputs)";
      return false;
    }
    RuleFile& joints = out.template emplace<RuleFile>();
    joints.keep = model;
    return make_supervised_joints(std::move(engine), configs, "fuzzy PID", joints, error);
  }
};

}  // namespace fuzzypid::controller::families
