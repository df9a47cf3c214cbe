#include "fuzzypid/sim/condition.hpp"

#include <cmath>
#include <cstdio>
#include <utility>

namespace fuzzypid::sim {

double PulseTrain::at(double t_s) const noexcept {
  if (accel_rad_s2 == 0.0 || t_s < start_s || t_s >= end_s || period_s <= 0.0) return 0.0;
  const double phase = t_s - start_s;
  const double cycle = std::floor(phase / period_s);
  if (phase - cycle * period_s >= width_s) return 0.0;
  return static_cast<long long>(cycle) % 2 == 0 ? accel_rad_s2 : -accel_rad_s2;
}

PulseTrain contact_pulses(double amplitude_rad_s2) noexcept {
  return PulseTrain{1.0, 4.0, 0.5, 0.1, amplitude_rad_s2};
}

namespace {

// "KEY must be within LO .. HI", or empty when v is finite and inside.
std::string out_of(const FieldRange& r, double v) {
  if (std::isfinite(v) && r.contains(v)) return {};
  char buf[160];
  std::snprintf(buf, sizeof buf, "%s must be within %g .. %g", r.key, r.lo, r.hi);
  return buf;
}

// Empty when v is 0 (off, or the plant's default: r.zero) or within r.
std::string off_or_within(const FieldRange& r, double v) {
  if (v == 0.0 || (std::isfinite(v) && r.contains(v))) return {};
  char buf[200];
  std::snprintf(buf, sizeof buf, "%s must be 0 (%s) or within %g .. %g", r.key, r.zero, r.lo, r.hi);
  return buf;
}

}  // namespace

bool JointEffects::operator==(const JointEffects& o) const noexcept {
  return plant_step_s == o.plant_step_s && delay_s == o.delay_s &&
         torque_bandwidth_hz == o.torque_bandwidth_hz && encoder_counts == o.encoder_counts &&
         coulomb_nm == o.coulomb_nm && stribeck_nm == o.stribeck_nm &&
         stribeck_velocity_rad_s == o.stribeck_velocity_rad_s &&
         coulomb_smoothing_rad_s == o.coulomb_smoothing_rad_s &&
         joint_resonance_hz == o.joint_resonance_hz &&
         joint_damping_ratio == o.joint_damping_ratio && backlash_rad == o.backlash_rad;
}

std::string JointEffects::validate() const {
  for (const auto& [range, value] :
       {std::pair{kPlantStepMsRange, plant_step_s * 1e3}, std::pair{kDelayMsRange, delay_s * 1e3},
        std::pair{kTorqueBandwidthRange, torque_bandwidth_hz},
        std::pair{kEncoderCountsRange, static_cast<double>(encoder_counts)},
        std::pair{kStribeckVelocityRange, stribeck_velocity_rad_s},
        std::pair{kCoulombSmoothingRange, coulomb_smoothing_rad_s},
        std::pair{kJointDampingRatioRange, joint_damping_ratio},
        std::pair{kBacklashRange, backlash_rad}})
    if (std::string bad = off_or_within(range, value); !bad.empty()) return bad;
  if (backlash_rad > 0.0 && joint_resonance_hz == robot::JointVector{})
    return "backlash_rad needs an elastic gear (joint_resonance_hz > 0)";
  for (const auto& [range, values] :
       {std::pair{kCoulombRange, coulomb_nm}, std::pair{kStribeckRange, stribeck_nm},
        std::pair{kJointResonanceRange, joint_resonance_hz}})
    for (double v : values)
      if (std::string bad = out_of(range, v); !bad.empty()) return bad;
  return {};
}

std::string Condition::validate() const {
  for (const auto& [range, value] :
       {std::pair{kPayloadScaleRange, payload_scale}, std::pair{kFrictionRange, friction_per_s},
        std::pair{kTorqueLimitRange, torque_limit_rad_s2}, std::pair{kContactRange, contact_rad_s2},
        std::pair{kNoisePositionRange, noise_position_rad},
        std::pair{kNoiseVelocityRange, noise_velocity_rad_s},
        std::pair{kInitialErrorRange, initial_error_rad}, std::pair{kPayloadKgRange, payload_kg}})
    if (std::string bad = out_of(range, value); !bad.empty()) return bad;
  if (!(payload_scale > 0.0)) return "payload_scale must be > 0";
  if (std::string bad = effects.validate(); !bad.empty()) return bad;
  // The plant keeps robot::kDelayCommands commands for the delay (robot/plant.hpp).
  if (effects.delay_s > 60.0 * robot.tick_s * (1.0 + 1e-9)) {
    char buf[120];
    std::snprintf(buf, sizeof buf, "delay_ms must be at most 60 ticks (%g ms at this tick)",
                  60.0 * robot.tick_s * 1e3);
    return buf;
  }
  if (gravity && dynamics != robot::PlantCoupling::Coupled)
    return "gravity needs the coupled dynamics (dynamics = coupled)";
  return robot.validate();
}

robot::PlantCoupling default_dynamics(const RobotSetup& robot) noexcept {
  return robot.urdf.empty() ? robot::PlantCoupling::Decoupled : robot::PlantCoupling::Coupled;
}

bool default_gravity(const RobotSetup& robot, robot::PlantCoupling dynamics) noexcept {
  return !robot.urdf.empty() && dynamics == robot::PlantCoupling::Coupled;
}

std::string FieldRange::text() const {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g .. %g", lo, hi);
  return buf;
}

bool RobotSetup::operator==(const RobotSetup& o) const noexcept {
  return urdf == o.urdf && base_link == o.base_link && tip_link == o.tip_link && path == o.path &&
         start_m == o.start_m && end_m == o.end_m && tick_s == o.tick_s &&
         armature_kgm2 == o.armature_kgm2 && ik_seed_rad == o.ik_seed_rad;
}

std::string RobotSetup::validate() const {
  if (!std::isfinite(tick_s) || tick_s < kMinTickS || tick_s > kMaxTickS)
    return "tick must be within " + kTickMsRange.text() + " ms";
  if (armature_kgm2)
    for (double a : *armature_kgm2)
      if (!kArmatureRange.contains(a))
        return "armature values must be within " + kArmatureRange.text() + " kg·m²";
  for (const auto* p : {&start_m, &end_m})
    if (*p)
      for (double v : **p)
        if (!std::isfinite(v) || std::fabs(v) > kMaxPathCoordinateM)
          return "path end points must be finite and within ±1 km of the base, m";
  if (ik_seed_rad)
    for (double v : *ik_seed_rad)
      if (!std::isfinite(v) || std::fabs(v) > 100.0) return "IK seed must be finite, rad";
  if (ik_seed_rad && path.empty())
    return "ik_seed (--ik-seed) applies only to a Cartesian path file (path, --path); the "
           "built-in line A -> B runs from its own start joints";
  return {};
}

const std::vector<Condition>& scenarios() {
  static const std::vector<Condition> all = [] {
    std::vector<Condition> v;
    Condition paper;
    paper.name = "paper";
    paper.description = "section 6: A -> B, nominal plant, exact measurements";
    v.push_back(paper);

    Condition light = paper;
    light.name = "payload-light";
    light.description = "link inertia x0.5 (lighter workpiece); controller unchanged";
    light.payload_scale = 0.5;
    v.push_back(light);

    Condition heavy = paper;
    heavy.name = "payload-heavy";
    heavy.description = "link inertia x2 (heavier workpiece); controller unchanged";
    heavy.payload_scale = 2.0;
    v.push_back(heavy);

    Condition friction = paper;
    friction.name = "friction";
    friction.description = "viscous friction b_i = 2 J^_i N·m·s/rad (none in the nominal plant)";
    friction.friction_per_s = 2.0;
    v.push_back(friction);

    Condition deburring = paper;
    deburring.name = "deburring";
    deburring.description =
        "contact-force pulses while moving: 0.1 s of +/-0.5 rad/s² x J^_i every 0.5 s, 1-4 s";
    deburring.contact_rad_s2 = 0.5;
    v.push_back(deburring);

    Condition noise = paper;
    noise.name = "noise";
    noise.description = "Gaussian measurement noise: 2e-4 rad on angles, 5e-3 rad/s on velocities";
    noise.noise_position_rad = 2e-4;
    noise.noise_velocity_rad_s = 5e-3;
    v.push_back(noise);

    Condition saturation = paper;
    saturation.name = "saturation";
    saturation.description = "actuator limit |tau_i| <= 0.1 rad/s² x J^_i";
    saturation.torque_limit_rad_s2 = 0.1;
    v.push_back(saturation);
    return v;
  }();
  return all;
}

const Condition* find_scenario(const std::string& name) {
  for (const auto& s : scenarios())
    if (s.name == name) return &s;
  return nullptr;
}

}  // namespace fuzzypid::sim
