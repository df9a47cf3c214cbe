#include "fuzzypid/sim/faults.hpp"

#include <cmath>
#include <cstdio>

namespace fuzzypid::sim {

namespace {

void record(JointFault& f, double t_s, double value) noexcept {
  if (f.ticks == 0) {
    f.first_t_s = t_s;
    f.first_value_rad = value;
  }
  ++f.ticks;
}

}  // namespace

bool FaultMonitor::observe(double t_s, const robot::JointVector& theta_d,
                           const robot::JointVector& theta) noexcept {
  bool faulted = false;
  for (std::size_t i = 0; i < robot::kNumJoints; ++i) {
    const double e = std::fabs(theta_d[i] - theta[i]);
    if (!(e <= divergence_rad_)) {
      record(faults_.divergence[i], t_s, e);
      faulted = true;
    }
    if (theta[i] < lower_rad_[i] || theta[i] > upper_rad_[i]) {
      record(faults_.joint_limit[i], t_s, theta[i]);
      faulted = true;
    }
  }
  if (faulted) ++faults_.ticks;
  return faulted;
}

bool FaultMonitor::observe(double t_s, const robot::JointVector& theta_d,
                           const robot::JointVector& theta, const robot::JointVector& torque_nm,
                           const std::array<bool, robot::kNumJoints>& at_limit) noexcept {
  bool cycling = false;
  for (std::size_t i = 0; i < robot::kNumJoints; ++i) {
    const int sign = torque_nm[i] > 0.0 ? 1 : (torque_nm[i] < 0.0 ? -1 : 0);
    if (at_limit[i] && sign != 0 && sign == -cycle_sign_[i]) {
      ++cycle_run_[i];
    } else {
      cycle_run_[i] = at_limit[i] && sign != 0 ? 1 : 0;
    }
    cycle_sign_[i] = at_limit[i] ? sign : 0;
    if (cycle_run_[i] >= kLimitCycleTicks) {
      record(faults_.limit_cycle[i], t_s, torque_nm[i]);
      cycling = true;
    }
  }
  // The tick counts once whichever kinds hold.
  const std::size_t before = faults_.ticks;
  const bool other = observe(t_s, theta_d, theta);
  if (cycling && faults_.ticks == before) ++faults_.ticks;
  return other || cycling;
}

std::vector<std::string> describe(const TrackingFaults& faults, double divergence_rad,
                                  const robot::JointVector& lower_rad,
                                  const robot::JointVector& upper_rad) {
  std::vector<std::string> lines;
  char buf[256];
  for (std::size_t i = 0; i < robot::kNumJoints; ++i) {
    const JointFault& d = faults.divergence[i];
    if (d.ticks != 0) {
      std::snprintf(buf, sizeof buf,
                    "joint %zu: |error| %.6g rad > %g rad at t = %.6g s (first of %zu ticks)",
                    i + 1, d.first_value_rad, divergence_rad, d.first_t_s, d.ticks);
      lines.emplace_back(buf);
    }
    const JointFault& l = faults.joint_limit[i];
    if (l.ticks != 0) {
      std::snprintf(buf, sizeof buf,
                    "joint %zu: angle %.6g rad outside its limits [%.6g, %.6g] rad at t = %.6g s "
                    "(first of %zu ticks)",
                    i + 1, l.first_value_rad, lower_rad[i], upper_rad[i], l.first_t_s, l.ticks);
      lines.emplace_back(buf);
    }
    const JointFault& c = faults.limit_cycle[i];
    if (c.ticks != 0) {
      std::snprintf(buf, sizeof buf,
                    "joint %zu: limit cycle: torque on its limits with alternating sign for %zu "
                    "ticks at t = %.6g s (first of %zu ticks): the loop is unstable, bounded "
                    "only by the torque limits",
                    i + 1, kLimitCycleTicks, c.first_t_s, c.ticks);
      lines.emplace_back(buf);
    }
  }
  return lines;
}

}  // namespace fuzzypid::sim
