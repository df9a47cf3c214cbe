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
  const auto [lo, hi] = std::minmax_element(theta_d.begin(), theta_d.end());
  const double excursion = *hi - *lo;
  const bool closed = excursion > 0.0 && std::fabs(theta_d.back() - theta_d.front()) <=
                                             kClosedPathTolerance * excursion;
  const double overshoot_base = closed ? std::max(excursion, travel) : travel;
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
  m.overshoot_pct = 100.0 * past / overshoot_base;
  if (last_outside == n) {
    m.settling_time_s = 0.0;
  } else if (last_outside + 1 == n) {
    m.settling_time_s = std::numeric_limits<double>::infinity();
  } else {
    m.settling_time_s = t_s[last_outside + 1];
  }
  return m;
}

namespace {

int sign_of(double x) noexcept {
  return x > 0.0 ? 1 : (x < 0.0 ? -1 : 0);
}

}  // namespace

double reversals_pct(const std::vector<double>& u) {
  const std::size_t n = u.size();
  if (n < 3) return 0.0;
  const auto [lo, hi] = std::minmax_element(u.begin(), u.end());
  const double h = kReversalThreshold * (*hi - *lo);
  std::size_t reversals = 0;
  int last = 0;  // sign of the last significant change, 0 before the first
  for (std::size_t k = 1; k < n; ++k) {
    const double d = u[k] - u[k - 1];
    if (!(std::fabs(d) > h)) continue;
    const int s = sign_of(d);
    if (last != 0 && s != last) ++reversals;
    last = s;
  }
  return 100.0 * static_cast<double>(reversals) / static_cast<double>(n - 2);
}

double sign_changes_pct(const std::vector<double>& u) {
  const std::size_t n = u.size();
  if (n < 2) return 0.0;
  std::size_t changes = 0;
  int last = sign_of(u[0]);  // sign of the last non-zero command, 0 before the first
  for (std::size_t k = 1; k < n; ++k) {
    const int s = sign_of(u[k]);
    if (s == 0) continue;
    if (last != 0 && s != last) ++changes;
    last = s;
  }
  return 100.0 * static_cast<double>(changes) / static_cast<double>(n - 1);
}

DriveMetrics drive_metrics(const std::vector<double>& t_s, const std::vector<double>& u,
                           const std::vector<double>& tau_nm, const std::vector<char>& saturated) {
  DriveMetrics m;
  const std::size_t n = u.size();
  if (n == 0 || t_s.size() != n || tau_nm.size() != n || saturated.size() != n) return m;
  m.reversals_pct = reversals_pct(u);
  m.sign_changes_pct = sign_changes_pct(u);
  std::size_t at_limit = 0;
  double sum_sq = 0.0;
  double variation = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    if (saturated[k] != 0) ++at_limit;
    sum_sq += tau_nm[k] * tau_nm[k];
    if (k > 0) variation += std::fabs(tau_nm[k] - tau_nm[k - 1]);
  }
  m.saturated_pct = 100.0 * static_cast<double>(at_limit) / static_cast<double>(n);
  m.tau_rms_nm = std::sqrt(sum_sq / static_cast<double>(n));
  const double duration = t_s.back() - t_s.front();
  m.torque_variation_nm_per_s = duration > 0.0 ? variation / duration : 0.0;
  return m;
}

}  // namespace fuzzypid::sim
