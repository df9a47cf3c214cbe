#include "fuzzypid/controller/controller_spec.hpp"

#include "fuzzypid/controller/families.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

namespace fuzzypid::controller {

namespace {

bool positive_finite(double v) {
  return std::isfinite(v) && v > 0.0;
}

}  // namespace

std::string format_double(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  std::string s = buf;
  if (s.find_first_of(".eE") == std::string::npos) s += ".0";
  return s;
}

std::string validate(const RuleTableSpec& t) {
  const auto centers_ok = [](const RuleTableSpec::Centers& c) {
    for (std::size_t k = 0; k < c.size(); ++k) {
      if (!std::isfinite(c[k]) || c[k] != -c[c.size() - 1 - k]) return false;
      if (k > 0 && !(c[k] > c[k - 1])) return false;
    }
    return true;
  };
  if (!centers_ok(t.error_centers) || !centers_ok(t.error_rate_centers))
    return "rule_table centers must be finite, increasing and symmetric about 0";
  for (const auto& table : t.ratio)
    for (const auto& row : table)
      for (double v : row)
        if (!positive_finite(v)) return "rule_table ratios must be finite and > 0";
  return {};
}

std::string validate(const ControllerSpec& s) {
  if (!positive_finite(s.units.tick_s)) return "units.tick_s must be finite and > 0";
  if (!s.gains.finite() || s.gains.kp < 0 || s.gains.ki < 0 || s.gains.kd < 0)
    return "gains must be finite and >= 0";
  for (double v : s.bandwidth_scale)
    if (!(v >= kMinBandwidthScale && v <= kMaxBandwidthScale))
      return "bandwidth_scale must be within [" + format_double(kMinBandwidthScale) + ", " +
             format_double(kMaxBandwidthScale) + "] on every joint";
  if (s.family.index() >= kFamilies.size()) return "unknown controller family";
  const FamilyTraits& traits = family_traits(s.family);
  const auto& sup = s.supervisor;
  if (traits.supervised()) {
    if (!positive_finite(sup.error_scale) || !positive_finite(sup.error_rate_scale))
      return "error_scale and error_rate_scale must be finite and > 0";
    for (double v : sup.output_scale) {
      if (!std::isfinite(v)) return "output_scale must be finite";
      if (traits.output_scale == OutputScale::Ratios && !(v > 0.0))
        return std::string("the ") + traits.name +
               " family's output_scale (gain ratios) must be > 0";
    }
  }
  if (!sup.rule_file.empty() && (!traits.rule_base || sup.rule_model == nullptr))
    return "a rule file belongs to a family with a rule base (fuzzy) and must be loaded "
           "(controller_file::load)";
  if (traits.rule_table)
    if (std::string bad = validate(sup.rule_table); !bad.empty()) return bad;
  if (std::string bad = with_family(
          s.family, [&](auto family) { return decltype(family)::validate(s); }, std::string());
      !bad.empty())
    return bad;
  const double lo[3] = {s.gain_min.kp, s.gain_min.ki, s.gain_min.kd};
  const double hi[3] = {s.gain_max.kp, s.gain_max.ki, s.gain_max.kd};
  for (int k = 0; k < 3; ++k)
    if (!(lo[k] >= 0.0) || std::isinf(lo[k]) || !(hi[k] >= lo[k]))
      return "gain bounds must satisfy 0 <= gain_min <= gain_max";
  // The supervised families clamp the retuned gains into [bounds] every tick; a nominal K0
  // outside them would be clamped on every tick without a word.
  if (traits.supervised()) {
    const double k0[3] = {s.gains.kp, s.gains.ki, s.gains.kd};
    const char* names[3] = {"kp", "ki", "kd"};
    for (int k = 0; k < 3; ++k)
      if (k0[k] < lo[k] || k0[k] > hi[k])
        return std::string("gains.") + names[k] + " = " + format_double(k0[k]) +
               " lies outside [bounds] " + format_double(lo[k]) + " .. " + format_double(hi[k]);
  }
  if (!(s.pid.derivative_filter_s >= 0.0) || !std::isfinite(s.pid.derivative_filter_s))
    return "derivative_filter_s must be finite and >= 0";
  if (s.pid.derivative == pid::DerivativeSource::Observer) {
    if (!(s.pid.observer_bandwidth_hz > 0.0 && s.pid.observer_bandwidth_hz <= 1e6))
      return "observer_bandwidth_hz must be within (0, 1e6] Hz with derivative = \"observer\"";
    if (s.pid.observer_delay_ticks < 0 || s.pid.observer_delay_ticks > pid::kMaxObserverDelayTicks)
      return "observer_delay_ticks must be 0 .. " + std::to_string(pid::kMaxObserverDelayTicks);
    if (s.units.gains != GainUnits::Acceleration)
      return "derivative = \"observer\" needs gains in acceleration units (its model reads the "
             "command as rad/s²)";
  } else if (s.pid.observer_bandwidth_hz != 0.0) {
    return "observer_bandwidth_hz applies only to derivative = \"observer\"";
  }
  return {};
}

}  // namespace fuzzypid::controller
