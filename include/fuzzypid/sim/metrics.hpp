// Tracking metrics of one joint, computed from the sampled rows of trajectory.csv alone (times
// t_k, reference theta_d, angle theta, error e = theta_d - theta; k = 0..K-1, tick dt):
//
//   travel          |theta_d(t_end) - theta(t_0)|: how far the joint must move, from where it
//                   starts to where the path ends (includes the initial error)
//   settling_time_s the time after which |e| stays within 2 % of travel: t_{j+1} for the last
//                   sample j outside the band, 0 if none is, +inf if the last sample is outside
//   overshoot_pct   100 * max(0, max_k(-s e_k)) / travel, s = sign(e_0) (or the direction of
//                   travel when e_0 = 0): how far the joint runs past its reference, opposite to
//                   where it started, relative to its travel
//   max_abs_error   max_k |e_k|, rad
//   max_abs_error_after_1s   max |e_k| over t_k >= 1 s (after the start transient), rad
//   rms_error       sqrt(mean_k e_k^2), rad
//   iae, itae       sum_k |e_k| dt and sum_k t_k |e_k| dt (rectangle rule over all K samples)
#pragma once

#include <cstddef>
#include <vector>

namespace fuzzypid::sim {

inline constexpr double kSettlingBand = 0.02;  // fraction of travel

struct JointMetrics {
  double settling_time_s = 0.0;
  double overshoot_pct = 0.0;
  double max_abs_error_rad = 0.0;
  double max_abs_error_after_1s_rad = 0.0;
  double rms_error_rad = 0.0;
  double iae = 0.0;   // rad·s
  double itae = 0.0;  // rad·s²
};

// All vectors have the same length K >= 1; dt_s is the tick.
[[nodiscard]] JointMetrics joint_metrics(const std::vector<double>& t_s,
                                         const std::vector<double>& theta_d,
                                         const std::vector<double>& theta,
                                         const std::vector<double>& error, double dt_s);

}  // namespace fuzzypid::sim
