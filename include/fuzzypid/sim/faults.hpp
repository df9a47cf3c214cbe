// Tracking faults of a run: what makes a result no result, counted tick by tick beside the
// controller's own faults (Status). A joint faults on a tick when
//   - it diverged: |e| = |theta_d - theta| > divergence_rad (or e is not a number), or
//   - its true angle theta left the URDF's joint limits: theta < lower or theta > upper
//     (a continuous joint has none), or
//   - it is in a limit cycle: its torque has been at a torque limit with the sign alternating on
//     kLimitCycleTicks consecutive ticks (given the torques, observe()'s second form). That is the
//     form a linearly unstable loop takes under torque limits -- an oscillation at the Nyquist
//     rate, bounded by the limits, which would never reach divergence_rad; a stable loop that
//     saturates (a large step) pushes one way, and one that reverses on every tick (measurement
//     noise) stays off the limits.
// sim::Experiment::run observes every tick of a run (RunResult::tracking_faults) and goes on;
// sim_ab and rt_loop name each fault on stderr and exit 1 unless --allow-faults. The tuner's
// early stop (RunLimits::max_error_rad) is a separate bound with the same default.
//
// observe() is noexcept and allocates nothing (the real-time loop calls it every tick).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "fuzzypid/robot/types.hpp"

namespace fuzzypid::sim {

// |e| above this is a divergence, rad: the tuner's default (tune::Objective::divergence_rad).
inline constexpr double kDefaultDivergenceRad = 1.0;

// One kind of fault of one joint over a run.
struct JointFault {
  std::size_t ticks = 0;                                        // ticks on which it held
  double first_t_s = std::numeric_limits<double>::quiet_NaN();  // the first of them, s
  // There: |e| (divergence) or theta (joint limit), rad.
  double first_value_rad = std::numeric_limits<double>::quiet_NaN();
};

// Consecutive ticks of saturated, sign-alternating torque that make a limit cycle.
inline constexpr std::size_t kLimitCycleTicks = 10;

struct TrackingFaults {
  std::array<JointFault, robot::kNumJoints> divergence{};
  std::array<JointFault, robot::kNumJoints> joint_limit{};
  // first_value_rad holds the torque, N·m, on the tick the cycle was first counted.
  std::array<JointFault, robot::kNumJoints> limit_cycle{};
  std::size_t ticks = 0;  // ticks on which any joint faulted (either kind)
  [[nodiscard]] bool any() const noexcept { return ticks != 0; }
};

// Which joints are at a torque limit: clamped by the plant, or held there by the controller's own
// output limit (the plant's limit over J^_i, so that J^_i u_i lands on it up to rounding).
[[nodiscard]] inline std::array<bool, robot::kNumJoints> at_torque_limit(
    const robot::JointVector& applied_nm, const std::array<bool, robot::kNumJoints>& clamped,
    const robot::JointVector& limit_nm) noexcept {
  std::array<bool, robot::kNumJoints> out{};
  for (std::size_t i = 0; i < robot::kNumJoints; ++i)
    out[i] = clamped[i] || std::fabs(applied_nm[i]) >= (1.0 - 1e-9) * limit_nm[i];
  return out;
}

class FaultMonitor {
 public:
  FaultMonitor() = default;
  // Limits as RobotModel gives them (infinite for a continuous joint); divergence_rad > 0.
  FaultMonitor(double divergence_rad, const robot::JointVector& lower_rad,
               const robot::JointVector& upper_rad) noexcept
      : divergence_rad_(divergence_rad), lower_rad_(lower_rad), upper_rad_(upper_rad) {}

  // One tick at t_s with reference theta_d and true angle theta; true when a joint faulted.
  bool observe(double t_s, const robot::JointVector& theta_d,
               const robot::JointVector& theta) noexcept;
  // The same, with the torque each joint received (N·m) and whether it was at its limit: limit
  // cycles are counted too.
  bool observe(double t_s, const robot::JointVector& theta_d, const robot::JointVector& theta,
               const robot::JointVector& torque_nm,
               const std::array<bool, robot::kNumJoints>& at_limit) noexcept;

  const TrackingFaults& faults() const noexcept { return faults_; }
  double divergence_rad() const noexcept { return divergence_rad_; }
  const robot::JointVector& lower_rad() const noexcept { return lower_rad_; }
  const robot::JointVector& upper_rad() const noexcept { return upper_rad_; }

 private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  double divergence_rad_ = kDefaultDivergenceRad;
  robot::JointVector lower_rad_{-kInf, -kInf, -kInf, -kInf, -kInf, -kInf};
  robot::JointVector upper_rad_{kInf, kInf, kInf, kInf, kInf, kInf};
  TrackingFaults faults_{};
  // Per joint: the length of the current run of saturated ticks of alternating sign, and the
  // sign of the last one (0: none).
  std::array<std::size_t, robot::kNumJoints> cycle_run_{};
  std::array<int, robot::kNumJoints> cycle_sign_{};
};

// One line per joint and kind of fault, e.g. "joint 3: |error| 1.78 rad > 1 rad at t = 2.35 s
// (first of 12 ticks)", "joint 2: angle 3.01 rad outside its limits [-2.97, 2.97] rad at
// t = 1.2 s (first of 4 ticks)" or "joint 4: limit cycle: torque on its limits with alternating
// sign for 10 ticks at t = 3.1 s (first of 20 ticks)"; empty when there is none.
[[nodiscard]] std::vector<std::string> describe(const TrackingFaults& faults, double divergence_rad,
                                                const robot::JointVector& lower_rad,
                                                const robot::JointVector& upper_rad);

}  // namespace fuzzypid::sim
