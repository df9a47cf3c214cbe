// A six-joint controller as a plain description (docs/tuning.md): the family, its gains and
// scales in stated units, the gain bounds, the PID options, the supervisor's data (the paper's
// tables, a rule base loaded from a .fis/.fll/.fcl file, a schedule or a tuned rule table), the
// feed-forward. How it was tuned (tune/record.hpp) and what certify found (margin_record.hpp) are
// records a controller file keeps beside it (controller_file::ControllerFile). No file format
// here: controller_file/ reads and writes it as TOML, codegen/ writes it as a C++ header,
// joint_controllers.hpp builds the runtime.
//
// A family is one file in families/ plus its supervisor (supervisor/), listed in families.hpp;
// code outside them asks its traits (family.hpp), never its name.
//
// Library fuzzypid::controller (set-up code: it allocates and reports errors). The controllers it
// builds (joint_controllers.hpp) run allocation-free.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>

#include "fuzzypid/controller/family.hpp"
#include "fuzzypid/enum_names.hpp"
#include "fuzzypid/fuzzy/engine.hpp"
#include "fuzzypid/fuzzy/operators.hpp"
#include "fuzzypid/paper.hpp"
#include "fuzzypid/pid/gains.hpp"
#include "fuzzypid/pid/pid.hpp"
#include "fuzzypid/supervisor/fuzzy_pid.hpp"

namespace fuzzypid::controller {

// ---------------------------------------------------------------------------------------------
// Vocabulary. Every enum is parsed from the same table that names it (parse_enum / to_string).

// u in rad/s² scaled by the nominal inertia (torque J^_i u_i), or a torque in N·m.
enum class GainUnits : std::uint8_t { Acceleration, Torque };
// Ki, Kd per tick (u = Kp e + Ki sum(e) + Kd (e_k - e_{k-1}), the paper's numbers) or continuous
// (u = Kp e + Ki int(e dt) + Kd de/dt).
enum class PidForm : std::uint8_t { PerTick, Continuous };

inline constexpr std::array<EnumName<GainUnits>, 2> kGainUnitsNames{
    {{GainUnits::Acceleration, "acceleration"}, {GainUnits::Torque, "torque"}}};
inline constexpr std::array<EnumName<PidForm>, 2> kPidFormNames{
    {{PidForm::PerTick, "per-tick"}, {PidForm::Continuous, "continuous"}}};
// The built-in tables (paper::Tables: as printed or with the two suspected misprints corrected)
// as a controller file's rule_base names them, and as sim_ab's --tables does.
inline constexpr std::array<EnumName<paper::Tables>, 2> kRuleBaseNames{
    {{paper::Tables::Printed, "paper-printed"}, {paper::Tables::Corrected, "paper-corrected"}}};
inline constexpr std::array<EnumName<paper::Tables>, 2> kPaperTablesNames{
    {{paper::Tables::Printed, "printed"}, {paper::Tables::Corrected, "corrected"}}};
inline constexpr std::array<EnumName<pid::DerivativeSource>, 3> kDerivativeSourceNames{
    {{pid::DerivativeSource::Rates, "rates"},
     {pid::DerivativeSource::Difference, "difference"},
     {pid::DerivativeSource::Observer, "observer"}}};
inline constexpr std::array<EnumName<pid::DerivativeOn>, 2> kDerivativeOnNames{
    {{pid::DerivativeOn::Error, "error"}, {pid::DerivativeOn::Measurement, "measurement"}}};
inline constexpr std::array<EnumName<pid::AntiWindup>, 3> kAntiWindupNames{
    {{pid::AntiWindup::None, "none"},
     {pid::AntiWindup::Clamping, "clamping"},
     {pid::AntiWindup::BackCalculation, "back-calculation"}}};
inline constexpr std::array<EnumName<supervisor::GainUpdate>, 2> kGainUpdateNames{
    {{supervisor::GainUpdate::Absolute, "absolute"},
     {supervisor::GainUpdate::Incremental, "incremental"}}};
inline constexpr std::array<EnumName<fuzzy::Conjunction>, 2> kConjunctionNames{
    {{fuzzy::Conjunction::Minimum, "min"}, {fuzzy::Conjunction::Product, "prod"}}};

[[nodiscard]] constexpr const char* to_string(GainUnits g) noexcept {
  return name_of(kGainUnitsNames, g);
}
[[nodiscard]] constexpr const char* to_string(PidForm f) noexcept {
  return name_of(kPidFormNames, f);
}
[[nodiscard]] constexpr const char* to_string(paper::Tables t) noexcept {
  return name_of(kRuleBaseNames, t);
}

// ---------------------------------------------------------------------------------------------
// Units: the one place where per-tick gains become continuous ones (Ki / dt, Kd dt).

[[nodiscard]] constexpr pid::Gains<double> to_continuous(const pid::Gains<double>& g, PidForm form,
                                                         double tick_s) noexcept {
  if (form == PidForm::Continuous) return g;
  return {g.kp, g.ki / tick_s, g.kd * tick_s};
}
[[nodiscard]] constexpr pid::Gains<double> from_continuous(const pid::Gains<double>& g,
                                                           PidForm form, double tick_s) noexcept {
  if (form == PidForm::Continuous) return g;
  return {g.kp, g.ki * tick_s, g.kd / tick_s};
}

// ---------------------------------------------------------------------------------------------
// The file's content.

struct Units {
  GainUnits gains = GainUnits::Acceleration;
  PidForm form = PidForm::PerTick;
  double tick_s = 0.05;  // the tick the per-tick gains refer to (and the controller's tick)
};

// FamilyTraits::rule_table: the rule table that refines the schedule (supervisor/rule_table.hpp). The
// partitions of x = Ke e and y = Kec ec are 7 sets each (NB NM NS ZO PS PM PB): triangles between
// neighbouring centers, shoulders outside; centers increasing and symmetric about 0. ratio[g][i][j]
// is the consequent of the rule "x is set i and y is set j" for gain g (kp, ki, kd): the factor on
// the schedule's gain at that node. A table of ones is the schedule itself.
struct RuleTableSpec {
  static constexpr std::size_t kSets = 7;
  using Centers = std::array<double, kSets>;
  using Table = std::array<std::array<double, kSets>, kSets>;

  Centers error_centers{-1.0, -2.0 / 3.0, -1.0 / 3.0, 0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0};
  Centers error_rate_centers{-1.0, -2.0 / 3.0, -1.0 / 3.0, 0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0};
  std::array<Table, 3> ratio = ones();

  [[nodiscard]] static constexpr std::array<Table, 3> ones() noexcept {
    std::array<Table, 3> t{};
    for (auto& table : t)
      for (auto& row : table)
        for (double& v : row)
          v = 1.0;
    return t;
  }
};

// The supervisor of a supervised family; which fields a family reads, its traits say
// (family.hpp).
struct SupervisorSpec {
  double error_scale = 1.0;       // Ke, universe units per rad
  double error_rate_scale = 1.0;  // Kec, universe units per rad/s
  // OutputScale::Scales: Sp, Si, Sd (gain units per table unit); OutputScale::Ratios: the
  // large-error ratios Rp, Ri, Rd of the schedule.
  std::array<double, 3> output_scale = {1.0, 1.0, 1.0};
  // FamilyTraits::rule_base: the gain update, the built-in tables and their AND.
  supervisor::GainUpdate gain_update = supervisor::GainUpdate::Absolute;
  paper::Tables rule_base = paper::Tables::Printed;
  fuzzy::Conjunction conjunction = fuzzy::Conjunction::Minimum;
  // FamilyTraits::rule_base: a .fis/.fll/.fcl rule base instead of the built-in tables (2 inputs
  // e, ec; 3 outputs dKp, dKi, dKd), as written in the file (relative to the file's folder), and
  // the model load() read from it (shared, immutable).
  std::string rule_file;
  std::shared_ptr<const fuzzy::EngineModel<double>> rule_model;
  RuleTableSpec rule_table{};  // FamilyTraits::rule_table
};

struct PidOptions {
  pid::DerivativeSource derivative = pid::DerivativeSource::Rates;
  pid::DerivativeOn derivative_on = pid::DerivativeOn::Error;
  pid::AntiWindup anti_windup = pid::AntiWindup::Clamping;
  double derivative_filter_s = 0.0;
  // derivative = "observer" (pid.hpp's velocity observer): its bandwidth, Hz (> 0), and the ticks
  // of computation delay it models (0 .. pid::kMaxObserverDelayTicks; the sim's delay_ms is
  // usually one tick). Only with acceleration gain units: the observer reads the command as rad/s².
  double observer_bandwidth_hz = 0.0;
  int observer_delay_ticks = 1;
};

// Model-based feed-forward added to the PID's torque.
struct Feedforward {
  // tau += g^(q_desired): the gravity torque of the nominal model (no payload) at the reference,
  // as industrial drives compensate gravity; without it the PID's integral carries the load.
  bool gravity = false;
};

// Joint i runs the file's loop s_i times faster (docs/tuning.md, "Per-joint bandwidth"): its
// gains are Kp s², Ki s³, Kd s (and so are K0, a supervisor's output scales in gain units and the
// gain bounds), its derivative filter's time constant Tf / s; the supervisor's Ke and Kec and an
// observer's bandwidth stay. On a double integrator J^ q'' = u that scales the closed loop's
// natural frequency by s and keeps its damping: one set of gains, shaped once, placed per joint.
inline constexpr std::size_t kSpecJoints = 6;
using BandwidthScale = std::array<double, kSpecJoints>;
inline constexpr BandwidthScale kUniformBandwidth{1.0, 1.0, 1.0, 1.0, 1.0, 1.0};
// The range a scale may take: three decades either way of the file's gains.
inline constexpr double kMinBandwidthScale = 1e-3;
inline constexpr double kMaxBandwidthScale = 1e3;

struct ControllerSpec {
  Family family{};  // the list's first: the fixed PID
  std::string description;
  Units units{};
  pid::Gains<double> gains = paper::kNominalGains<double>;  // pid: the gains; else K0
  BandwidthScale bandwidth_scale = kUniformBandwidth;       // per joint, s_i (above)
  SupervisorSpec supervisor{};                              // supervised families only
  pid::Gains<double> gain_min = {0.0, 0.0, 0.0};  // bounds on the retuned gains (file units)
  pid::Gains<double> gain_max = {std::numeric_limits<double>::infinity(),
                                 std::numeric_limits<double>::infinity(),
                                 std::numeric_limits<double>::infinity()};
  PidOptions pid{};
  Feedforward feedforward{};
};

// A value as controller files and messages write it: "%.17g", always with a '.', 'e', "inf" or
// "nan" (so TOML reads it as a float).
[[nodiscard]] std::string format_double(double v);

// The paper's controllers in the sim's default units (acceleration, per-tick, 0.05 s); defined
// with their families (src/controller/families/).
[[nodiscard]] ControllerSpec paper_pid();
[[nodiscard]] ControllerSpec paper_fuzzy();

// The fuzzy family's description of a fuzzy-rules controller `rules` whose rule table was written
// as a rule file (rulefile::rule_table_to_fll/fcl/fis): the same units, K0, Ke, Kec, bounds, PID
// options and feed-forward; output_scale S = K0 (file units) and the absolute update, so
// K = K0 + K0 dK with dK = ratio - 1 as the file encodes it. `rule_file` is the path the new file
// names (relative to its folder), `model` the rule file as loaded (it may be null until then:
// validate() wants it); `description` replaces the description.
[[nodiscard]] ControllerSpec fuzzy_from_rule_table(
    const ControllerSpec& rules, std::string rule_file,
    std::shared_ptr<const fuzzy::EngineModel<double>> model, std::string description);

// Checks the values (finite, positive where needed, bounds ordered, family-specific settings).
// Returns an empty string or what is wrong.
[[nodiscard]] std::string validate(const ControllerSpec& spec);
// The same for a rule table alone (centers increasing and symmetric, ratios finite and > 0).
[[nodiscard]] std::string validate(const RuleTableSpec& table);

}  // namespace fuzzypid::controller
