#include "fuzzypid/sim/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fuzzypid::sim {

Condition Sweep::at(const Condition& base, double v) const {
  Condition c = base;
  switch (parameter) {
    case SweepParameter::PayloadScale:
      c.payload_scale = v;
      break;
    case SweepParameter::TorqueLimit:
      c.torque_limit_rad_s2 = v;
      break;
  }
  return c;
}

std::array<std::size_t, 2> longest_true_stretch(const std::vector<bool>& v) {
  std::size_t best_first = 0, best_count = 0;
  for (std::size_t k = 0; k < v.size();) {
    if (!v[k]) {
      ++k;
      continue;
    }
    std::size_t j = k;
    while (j < v.size() && v[j])
      ++j;
    if (j - k > best_count) {
      best_first = k;
      best_count = j - k;
    }
    k = j;
  }
  return {best_first, best_count};
}

SweepResult run_sweep(const Experiment& experiment, const Condition& base,
                      const controller::ControllerSpec& spec, const Sweep& sweep,
                      const SweepBounds& bounds) {
  SweepResult out;
  const double tick = experiment.options().tick_s;
  const RunResult nominal = experiment.run(base, spec);
  if (!nominal.ok) {
    out.error = base.name + ": " + nominal.error;
    return out;
  }
  // The same sum as each point's, so that the nominal value's ratio is exactly 1.
  out.nominal_itae = summarize(run_metrics(nominal.rows, tick)).itae;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<bool> usable;
  for (int k = 0; k < sweep.count; ++k) {
    SweepPoint p;
    p.value = sweep.value(k);
    RunLimits limits;
    // A divergence is far outside anything usable: it ends the run early.
    limits.max_error_rad = bounds.divergence_rad;
    limits.divergence_rad = bounds.divergence_rad;
    const RunResult r = experiment.run(sweep.at(base, p.value), spec, limits);
    if (!r.ok) {
      out.error = std::string(name_of(kSweepParameterNames, sweep.parameter)) + "=" +
                  std::to_string(p.value) + ": " + r.error;
      out.points.clear();
      return out;
    }
    const RunSummary s = summarize(run_metrics(r.rows, tick));
    p.diverged = r.diverged;
    p.itae = r.diverged ? kInf : s.itae;
    p.max_overshoot_pct = r.diverged ? kInf : s.max_overshoot_pct;
    p.fault_ticks = r.fault_ticks;
    if (r.fault_ticks != 0) {
      const std::vector<std::string> lines =
          describe(r.tracking_faults, bounds.divergence_rad, experiment.model().lower_limits_rad(),
                   experiment.model().upper_limits_rad());
      if (!lines.empty()) p.first_fault = lines.front();
    }
    p.usable = !r.diverged && r.fault_ticks == 0 && std::isfinite(s.itae) &&
               s.max_overshoot_pct <= bounds.overshoot_pct &&
               s.itae <= bounds.itae_ratio * out.nominal_itae;
    usable.push_back(p.usable);
    out.points.push_back(std::move(p));
  }
  const auto [first, count] = longest_true_stretch(usable);
  out.usable_first = first;
  out.usable_count = count;
  out.ok = true;
  return out;
}

}  // namespace fuzzypid::sim
