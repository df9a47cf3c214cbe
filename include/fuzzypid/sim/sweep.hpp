// A robustness sweep (sim_ab --sweep): one condition's payload scale or torque limit stepped over
// evenly spaced values with one controller, each run judged usable or not, and the longest stretch
// of consecutive usable values. A run is usable when it neither diverges nor faults
// (sim/faults.hpp), its ITAE is finite and at most `itae_ratio` times the nominal run's (the
// condition as given), and no joint overshoots more than `overshoot_pct`.
//
// Library fuzzypid::sim (set-up and offline: allocates, reports errors as text).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzzypid/controller/controller_spec.hpp"
#include "fuzzypid/enum_names.hpp"
#include "fuzzypid/sim/condition.hpp"
#include "fuzzypid/sim/experiment.hpp"
#include "fuzzypid/sim/faults.hpp"

namespace fuzzypid::sim {

enum class SweepParameter : std::uint8_t {
  PayloadScale,  // Condition::payload_scale
  TorqueLimit,   // Condition::torque_limit_rad_s2
};
inline constexpr std::array<EnumName<SweepParameter>, 2> kSweepParameterNames{
    {{SweepParameter::PayloadScale, "payload-scale"},
     {SweepParameter::TorqueLimit, "torque-limit"}}};

// N >= 1 evenly spaced values of a parameter from LO to HI, both included (sim_ab --sweep
// PARAMETER=LO:HI:N).
struct Sweep {
  SweepParameter parameter = SweepParameter::PayloadScale;
  double lo = 0.0;
  double hi = 0.0;
  int count = 0;
  // The k-th value (0 <= k < count).
  [[nodiscard]] double value(int k) const noexcept {
    return count == 1 ? lo : lo + (hi - lo) * static_cast<double>(k) / (count - 1);
  }
  // `base` with the swept parameter set to `v`.
  [[nodiscard]] Condition at(const Condition& base, double v) const;
};

struct SweepBounds {
  double overshoot_pct = 20.0;  // usable while the worst joint's overshoot is at most this, %
  double itae_ratio = 3.0;      // usable while ITAE <= this x the nominal run's ITAE
  // A joint past this error faults and ends the run early (diverged), rad.
  double divergence_rad = kDefaultDivergenceRad;
};

struct SweepPoint {
  double value = 0.0;
  double itae = 0.0;               // summed over the joints; +inf when the run diverged
  double max_overshoot_pct = 0.0;  // worst joint; +inf when the run diverged
  std::size_t fault_ticks = 0;
  bool diverged = false;
  bool usable = false;
  std::string first_fault;  // the first line of the run's faults (sim::describe), if any
};

struct SweepResult {
  bool ok = false;
  std::string error;  // when !ok: the run that failed and why
  double nominal_itae = 0.0;
  std::vector<SweepPoint> points;  // one per value, in order
  // The longest stretch of consecutive usable points (the first such when several tie):
  // points[usable_first .. usable_first + usable_count); usable_count = 0 when none is.
  std::size_t usable_first = 0;
  std::size_t usable_count = 0;
};

// Runs `spec` on `base` (the nominal run), then at every value of `sweep`.
[[nodiscard]] SweepResult run_sweep(const Experiment& experiment, const Condition& base,
                                    const controller::ControllerSpec& spec, const Sweep& sweep,
                                    const SweepBounds& bounds);

// The longest stretch of consecutive true values: {first, count}; {0, 0} when there is none.
[[nodiscard]] std::array<std::size_t, 2> longest_true_stretch(const std::vector<bool>& v);

}  // namespace fuzzypid::sim
