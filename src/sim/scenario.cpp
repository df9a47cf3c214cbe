#include "fuzzypid/sim/scenario.hpp"

#include <cmath>

namespace fuzzypid::sim {

double PulseTrain::at(double t_s) const noexcept {
  if (accel_rad_s2 == 0.0 || t_s < start_s || t_s >= end_s || period_s <= 0.0) return 0.0;
  const double phase = t_s - start_s;
  const double cycle = std::floor(phase / period_s);
  if (phase - cycle * period_s >= width_s) return 0.0;
  return static_cast<long long>(cycle) % 2 == 0 ? accel_rad_s2 : -accel_rad_s2;
}

const std::vector<Scenario>& scenarios() {
  static const std::vector<Scenario> all = [] {
    std::vector<Scenario> v;
    Scenario paper;
    paper.name = "paper";
    paper.description = "section 6: A -> B, nominal plant, exact measurements";
    v.push_back(paper);

    Scenario light = paper;
    light.name = "payload-light";
    light.description = "link inertia x0.5 (lighter workpiece); controller unchanged";
    light.inertia_scale = 0.5;
    v.push_back(light);

    Scenario heavy = paper;
    heavy.name = "payload-heavy";
    heavy.description = "link inertia x2 (heavier workpiece); controller unchanged";
    heavy.inertia_scale = 2.0;
    v.push_back(heavy);

    Scenario friction = paper;
    friction.name = "friction";
    friction.description = "viscous friction b_i = 2 J^_i N·m·s/rad (none in the nominal plant)";
    friction.damping_per_s = 2.0;
    v.push_back(friction);

    Scenario deburring = paper;
    deburring.name = "deburring";
    deburring.description =
        "contact-force pulses while moving: 0.1 s of +/-0.5 rad/s² x J^_i every 0.5 s, 1-4 s";
    deburring.pulses = PulseTrain{1.0, 4.0, 0.5, 0.1, 0.5};
    v.push_back(deburring);

    Scenario noise = paper;
    noise.name = "noise";
    noise.description = "Gaussian measurement noise: 2e-4 rad on angles, 5e-3 rad/s on velocities";
    noise.position_noise_rad = 2e-4;
    noise.velocity_noise_rad_s = 5e-3;
    v.push_back(noise);

    Scenario saturation = paper;
    saturation.name = "saturation";
    saturation.description = "actuator limit |tau_i| <= 0.1 rad/s² x J^_i";
    saturation.accel_limit_rad_s2 = 0.1;
    v.push_back(saturation);
    return v;
  }();
  return all;
}

const Scenario* find_scenario(const std::string& name) {
  for (const auto& s : scenarios())
    if (s.name == name) return &s;
  return nullptr;
}

}  // namespace fuzzypid::sim
