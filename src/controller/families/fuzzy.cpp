// The fuzzy family's set-up code that is not a template (families/fuzzy.hpp).
#include "fuzzypid/controller/families/fuzzy.hpp"

#include <utility>

#include "fuzzypid/controller/families.hpp"

namespace fuzzypid::controller {

ControllerSpec paper_fuzzy() {
  ControllerSpec s;
  s.family = family_of<families::Fuzzy>();
  s.description =
      "the paper's fuzzy PID (section 6 gains, Tables 2-4 as printed, unit scales, Eq. 6)";
  return s;
}

ControllerSpec fuzzy_from_rule_table(const ControllerSpec& rules, std::string rule_file,
                                     std::shared_ptr<const fuzzy::EngineModel<double>> model,
                                     std::string description) {
  ControllerSpec s;
  s.family = family_of<families::Fuzzy>();
  s.description = std::move(description);
  s.units = rules.units;
  s.gains = rules.gains;
  s.bandwidth_scale = rules.bandwidth_scale;
  s.supervisor.error_scale = rules.supervisor.error_scale;
  s.supervisor.error_rate_scale = rules.supervisor.error_rate_scale;
  // S = K0 in file units: fuzzy_pid_config converts S like the gains, so S = K0 per tick or
  // continuous alike (fuzzy-rules uses the converted K0 as S directly).
  s.supervisor.output_scale = {rules.gains.kp, rules.gains.ki, rules.gains.kd};
  s.supervisor.gain_update = supervisor::GainUpdate::Absolute;
  s.supervisor.rule_file = std::move(rule_file);
  s.supervisor.rule_model = std::move(model);
  s.gain_min = rules.gain_min;
  s.gain_max = rules.gain_max;
  s.pid = rules.pid;
  s.feedforward = rules.feedforward;
  return s;
}

}  // namespace fuzzypid::controller
