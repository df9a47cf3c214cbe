// Named variations of the section 6 experiment that probe what fuzzy PID is claimed to be for
// (section 3: "the current workpiece is different from the previous one"). Each changes the plant
// or the measurements; the controllers are always the same.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace fuzzypid::sim {

// A disturbance torque pulse train, scaled per joint by the nominal inertia J^_i (so the same
// pulse gives every joint the same disturbing acceleration): from start_s to end_s, every
// period_s, a pulse of width_s seconds of +/- accel_rad_s2 (sign alternating).
struct PulseTrain {
  double start_s = 0.0;
  double end_s = 0.0;
  double period_s = 0.5;
  double width_s = 0.1;
  double accel_rad_s2 = 0.0;  // 0 = no pulses

  // Disturbing acceleration at time t (the plant multiplies it by J^_i).
  double at(double t_s) const noexcept;
};

struct Scenario {
  std::string name;
  std::string description;
  double inertia_scale = 1.0;         // multiplies the links' inertia (payload); armature unchanged
  double damping_per_s = 0.0;         // viscous damping b_i = damping_per_s * J^_i, N·m·s/rad
  PulseTrain pulses{};                // deburring contact force
  double position_noise_rad = 0.0;    // std. dev. of Gaussian noise on measured angles
  double velocity_noise_rad_s = 0.0;  // std. dev. on measured velocities
  double accel_limit_rad_s2 = 0.0;    // |tau_i| <= limit * J^_i (0: the URDF effort limits)
};

// The scenarios in the order `--scenario all` runs them; "paper" first.
[[nodiscard]] const std::vector<Scenario>& scenarios();
// nullptr when no scenario has that name.
[[nodiscard]] const Scenario* find_scenario(const std::string& name);

}  // namespace fuzzypid::sim
