// Tracking metrics of one joint, computed from the sampled rows of trajectory.csv alone (times
// t_k, reference theta_d, angle theta, error e = theta_d - theta; k = 0..K-1, tick dt):
//
//   travel          |theta_d(t_end) - theta(t_0)|: how far the joint must move, from where it
//                   starts to where the path ends (includes the initial error)
//   excursion       max_k theta_d - min_k theta_d: how far the reference moves along the path
//   closed          the joint's reference ends where it starts: excursion > 0 and
//                   |theta_d(t_end) - theta_d(t_0)| <= kClosedPathTolerance * excursion (a closed
//                   contour, where travel is only the initial error)
//   settling_time_s the time after which |e| stays within 2 % of travel: t_{j+1} for the last
//                   sample j outside the band, 0 if none is, +inf if the last sample is outside
//   overshoot_pct   100 * max(0, max_k(-s e_k)) / D, s = sign(e_0) (or the direction of
//                   travel when e_0 = 0): how far the joint runs past its reference, opposite to
//                   where it started, relative to D = travel on an open path and
//                   D = max(excursion, travel) on a closed one (relative to the start error
//                   alone, a contour's ordinary tracking lag would read as hundreds of percent)
//   max_abs_error   max_k |e_k|, rad
//   max_abs_error_after_1s   max |e_k| over t_k >= 1 s (after the start transient), rad
//   rms_error       sqrt(mean_k e_k^2), rad
//   iae, itae       sum_k |e_k| dt and sum_k t_k |e_k| dt (rectangle rule over all K samples)
//
// What the drive of one joint feels, from the controller's command u_k (trajectory.csv `u`, in
// the controller's units), the torque the plant received tau_k (`tau_nm`: held over the step
// that starts at t_k; the last sample, which starts no step, repeats the one before) and whether
// the plant held tau_k at a torque limit (k = 0..K-1):
//
//   reversals_pct   the command's direction reverses: with the changes d_k = u_k - u_{k-1}
//                   (k = 1..K-1) and the threshold h = kReversalThreshold * (max_k u_k -
//                   min_k u_k), a change is significant when |d_k| > h; tick k is a reversal
//                   when d_k is significant and its sign is opposite to that of the last
//                   significant change before it. 100 * reversals / (K - 2) (0 when K < 3).
//                   A command ringing at the Nyquist rate reverses on every tick (100 %), a
//                   smooth one at most once per extremum (none where every tick's change is
//                   below h), and a constant offset (gravity) changes nothing.
//   sign_changes_pct  tick k (k = 1..K-1) is a sign change when u_k != 0 and its sign is
//                   opposite to that of the last non-zero u before it. 100 * changes / (K - 1)
//                   (0 when K < 2). A zero command is no sign: 1, 0, -1 is one change.
//   saturated_pct   100 * (ticks at a torque limit) / K
//   tau_rms_nm      sqrt(mean_k tau_k^2), N·m
//   torque_variation_nm_per_s  the total variation sum_{k=1}^{K-1} |tau_k - tau_{k-1}| divided
//                   by the run's duration t_{K-1} - t_0 (0 when it is 0), N·m/s
#pragma once

#include <cstddef>
#include <vector>

namespace fuzzypid::sim {

inline constexpr double kSettlingBand = 0.02;         // fraction of travel
inline constexpr double kClosedPathTolerance = 0.01;  // fraction of the excursion
inline constexpr double kReversalThreshold = 0.01;    // fraction of the command's range

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

struct DriveMetrics {
  double reversals_pct = 0.0;
  double sign_changes_pct = 0.0;
  double saturated_pct = 0.0;
  double tau_rms_nm = 0.0;
  double torque_variation_nm_per_s = 0.0;
};

// The reversal and sign-change counts of a command alone (percentages as defined above).
[[nodiscard]] double reversals_pct(const std::vector<double>& u);
[[nodiscard]] double sign_changes_pct(const std::vector<double>& u);

// All vectors have the same length K (else, or when K = 0, all zero); saturated[k] != 0 when
// the plant held tau_k at a torque limit.
[[nodiscard]] DriveMetrics drive_metrics(const std::vector<double>& t_s,
                                         const std::vector<double>& u,
                                         const std::vector<double>& tau_nm,
                                         const std::vector<char>& saturated);

}  // namespace fuzzypid::sim
