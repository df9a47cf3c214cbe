#include "fuzzypid/sim/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fuzzypid::sim {

JointMetrics joint_metrics(const std::vector<double>& t_s, const std::vector<double>& theta_d,
                           const std::vector<double>& theta, const std::vector<double>& error,
                           double dt_s) {
  JointMetrics m;
  const std::size_t n = error.size();
  if (n == 0 || t_s.size() != n || theta_d.size() != n || theta.size() != n) return m;

  const double travel = std::max(std::fabs(theta_d.back() - theta.front()), 1e-12);
  const double band = kSettlingBand * travel;
  double s = error.front() > 0.0 ? 1.0 : (error.front() < 0.0 ? -1.0 : 0.0);
  if (s == 0.0) s = theta_d.back() >= theta_d.front() ? -1.0 : 1.0;

  double sum_sq = 0.0;
  double past = 0.0;
  std::size_t last_outside = n;  // n: never outside
  for (std::size_t k = 0; k < n; ++k) {
    const double e = error[k];
    const double a = std::fabs(e);
    m.max_abs_error_rad = std::max(m.max_abs_error_rad, a);
    if (t_s[k] >= 1.0) m.max_abs_error_after_1s_rad = std::max(m.max_abs_error_after_1s_rad, a);
    sum_sq += e * e;
    m.iae += a * dt_s;
    m.itae += t_s[k] * a * dt_s;
    past = std::max(past, -s * e);
    if (a > band) last_outside = k;
  }
  m.rms_error_rad = std::sqrt(sum_sq / static_cast<double>(n));
  m.overshoot_pct = 100.0 * past / travel;
  if (last_outside == n) {
    m.settling_time_s = 0.0;
  } else if (last_outside + 1 == n) {
    m.settling_time_s = std::numeric_limits<double>::infinity();
  } else {
    m.settling_time_s = t_s[last_outside + 1];
  }
  return m;
}

}  // namespace fuzzypid::sim
