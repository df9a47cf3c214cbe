// The fuzzy-rules family: K = K0 (1 + (R - 1) w(Ke e, Kec ec)) T(Ke e, Kec ec), the schedule
// refined by a tuned 7x7 rule table per gain over a tunable partition (supervisor/rule_table.hpp).
#pragma once

#include <memory>
#include <string>

#include "fuzzypid/controller/controller_spec.hpp"
#include "fuzzypid/controller/family.hpp"
#include "fuzzypid/controller/runtime.hpp"
#include "fuzzypid/supervisor/rule_table.hpp"

namespace fuzzypid::controller {

// The rule-table supervisor a description gives (its supervisor.rule_table and the schedule's
// ratios output_scale), for any family whose traits carry a rule table.
[[nodiscard]] inline supervisor::RuleTable<double> rule_table(const ControllerSpec& spec) {
  const RuleTableSpec& t = spec.supervisor.rule_table;
  supervisor::RuleTable<double> r;
  r.schedule_ratio = spec.supervisor.output_scale;
  r.table = t.ratio;
  r.e_centers = t.error_centers;
  r.ec_centers = t.error_rate_centers;
  return r;
}

namespace families {

struct FuzzyRules {
  static constexpr FamilyTraits kTraits{
      "fuzzy-rules",
      "K = K0 (1 + (R - 1) min(1, Ke|e| + Kec|ec|)) T(Ke e, Kec ec): the schedule refined by a "
      "7x7 rule table per gain (zero-order Sugeno, product AND) over a tunable partition",
      OutputScale::Ratios, false, true};
  using Runtimes = std::tuple<SupervisedJoints<supervisor::RuleTable<double>>>;

  [[nodiscard]] static std::string validate(const ControllerSpec& /*spec*/) { return {}; }

  // K = K0 + K0 dK with dK = ratio - 1 (supervisor/rule_table.hpp).
  static void configure(const ControllerSpec& /*spec*/,
                        supervisor::FuzzyPidConfig<double>& config) noexcept {
    const pid::Gains<double>& k0 = config.pid.gains;
    config.output_scale = {k0.kp, k0.ki, k0.kd};
    config.gain_update = supervisor::GainUpdate::Absolute;
  }

  // The header export of the supervisor (family.hpp, SupervisorCode). `code` writes what this
  // file cannot: code.literal(v), an exact literal of v as Scalar, and code.rule_base(model,
  // file), a rule file's model and its supervisor.
  template <class Code>
  [[nodiscard]] static SupervisorCode header_code(const ControllerSpec& spec, const Code& code) {
    const supervisor::RuleTable<double> t = rule_table(spec);
    const auto list = [&code](const auto& values) {
      std::string out = "{";
      for (std::size_t k = 0; k < values.size(); ++k)
        out += (k == 0 ? "" : ", ") + code.literal(values[k]);
      return out + "}";
    };
    std::string d =
        "template <class Scalar>\nusing Supervisor = fuzzypid::supervisor::RuleTable<Scalar>;\n\n"
        "// The shared, immutable supervisor the joints point to: the schedule's ratios R, the\n"
        "// rule table per gain (rows: sets of Ke e, columns: sets of Kec ec) and the centers.\n"
        "template <class Scalar>\ninline constexpr Supervisor<Scalar> kSupervisor{\n";
    d += "    " + list(t.schedule_ratio) + ",\n    {{\n";
    for (const auto& table : t.table) {
      d += "        {{\n";
      for (const auto& row : table)
        d += "            " + list(row) + ",\n";
      d += "        }},\n";
    }
    d += "    }},\n";
    d += "    " + list(t.e_centers) + ",\n";
    d += "    " + list(t.ec_centers) + "};\n";
    d += "static_assert(kSupervisor<double>.valid() && kSupervisor<float>.valid());\n\n";
    return {
        "#include \"fuzzypid/supervisor/fuzzy_pid.hpp\"\n#include "
        "\"fuzzypid/supervisor/rule_table.hpp\"\n",
        d};
  }

  template <class Runtime>
  [[nodiscard]] static bool build(const ControllerSpec& spec, const JointConfigs& configs,
                                  Runtime& out, std::string& error) {
    auto table = std::make_unique<const supervisor::RuleTable<double>>(rule_table(spec));
    if (!table->valid()) {
      error = "invalid rule table (centers increasing and symmetric, ratios finite and > 0)";
      return false;
    }
    using Joints = SupervisedJoints<supervisor::RuleTable<double>>;
    return make_supervised_joints(std::move(table), configs, "fuzzy-rules PID",
                                  out.template emplace<Joints>(), error);
  }
};

}  // namespace families
}  // namespace fuzzypid::controller
