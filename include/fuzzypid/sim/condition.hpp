// Conditions of the section 6 experiment: a plant variant x a path x a start state. Every field is
// settable from sim_ab's command line and from condition-set files (condition_set.hpp); the named
// scenarios are shorthands for conditions.
//
// The controller is never told about the condition: it keeps the nominal inertia J^_i (of the
// nominal plant at the start of the A -> B path), and friction, torque limits and contact forces
// are given relative to that J^_i so that every joint sees the same accelerations.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "fuzzypid/robot/plant.hpp"
#include "fuzzypid/robot/types.hpp"

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

// The deburring contact: 0.1 s pulses of +/- amplitude every 0.5 s from 1 s to 4 s.
[[nodiscard]] PulseTrain contact_pulses(double amplitude_rad_s2) noexcept;

// The robot, path and tick a condition runs on: what an Experiment is built from. The defaults are
// the paper's: the bundled ER50-C20 following the straight line A -> B at a 50 ms tick.
struct RobotSetup {
  std::string urdf;       // empty: the bundled ER50-C20 (robot::default_urdf_path())
  std::string base_link;  // empty: the URDF's root link
  std::string tip_link;   // empty: the end of the unique chain below the base
  std::string path;       // path CSV (robot/path_file.hpp); empty: the section 6 line A -> B
  // The section 6 line's end points in the base frame, m (used when `path` is empty); nullopt:
  // the paper's A and B.
  std::optional<std::array<double, 3>> start_m, end_m;
  double tick_s = 0.05;  // controller tick (section 6: 0.05 s)
  // Reflected motor inertia, kg·m²; nullopt: the ER50's estimates for the bundled ER50, 0 for any
  // other URDF (a URDF has no armature field).
  std::optional<robot::JointVector> armature_kgm2;
  // Seed of the first inverse kinematics of a Cartesian path; nullopt: the middle of each joint's
  // limits (robot::default_ik_seed). Refused with the built-in line or a joint path, which it
  // would not change.
  std::optional<robot::JointVector> ik_seed_rad;

  [[nodiscard]] bool operator==(const RobotSetup& o) const noexcept;
  [[nodiscard]] bool operator!=(const RobotSetup& o) const noexcept { return !(*this == o); }
  // Empty, or what is wrong.
  [[nodiscard]] std::string validate() const;
};

// The one table of ranges of the condition fields, used by the command line (sim_ab's options of
// the same names) and by Condition::validate() for condition files alike. Bounds are inclusive.
struct FieldRange {
  const char* key;  // condition-file key; the option is "--" + key with '_' -> '-'
  double lo;
  double hi;
  // What 0 means for a key of JointEffects, which takes 0 outside its range ("none", "ideal",
  // "the plant's default"); the messages say it.
  const char* zero = "off";
  [[nodiscard]] constexpr bool contains(double v) const noexcept { return v >= lo && v <= hi; }
  // "lo .. hi" as the messages give it (printf's %g), so that no message restates a bound.
  [[nodiscard]] std::string text() const;
};
inline constexpr FieldRange kPayloadScaleRange{"payload_scale", 1e-3, 1e3};
inline constexpr FieldRange kFrictionRange{"friction", 0.0, 1e4};            // 1/s
inline constexpr FieldRange kTorqueLimitRange{"torque_limit", 0.0, 1e6};     // rad/s²
inline constexpr FieldRange kContactRange{"contact", -1e4, 1e4};             // rad/s²
inline constexpr FieldRange kNoisePositionRange{"noise[0]", 0.0, 1.0};       // rad
inline constexpr FieldRange kNoiseVelocityRange{"noise[1]", 0.0, 100.0};     // rad/s
inline constexpr FieldRange kInitialErrorRange{"initial_error", -1.0, 1.0};  // rad
inline constexpr FieldRange kPayloadKgRange{"payload_kg", 0.0, 1e4};         // kg
inline constexpr FieldRange kTickMsRange{"tick_ms", 0.1, 1000.0};            // ms
inline constexpr FieldRange kArmatureRange{"armature", 0.0, 1e6};            // kg·m²
// What real joints have (JointEffects); each takes 0 (off, or the plant's default: `zero` says
// which) and otherwise a value within its range.
inline constexpr FieldRange kPlantStepMsRange{"plant_step_ms", 1e-3, 1000.0, "the default step"};
inline constexpr FieldRange kDelayMsRange{"delay_ms", 0.0, 1000.0, "none"};                   // ms
inline constexpr FieldRange kTorqueBandwidthRange{"torque_bandwidth_hz", 0.1, 1e5, "ideal"};  // Hz
inline constexpr FieldRange kEncoderCountsRange{"encoder_counts", 4.0, 1e12,
                                                "exact"};                          // per revolution
inline constexpr FieldRange kCoulombRange{"coulomb_nm", 0.0, 1e6};                 // N·m
inline constexpr FieldRange kStribeckRange{"stribeck_nm", 0.0, 1e6};               // N·m
inline constexpr FieldRange kJointResonanceRange{"joint_resonance_hz", 0.0, 1e4};  // Hz
inline constexpr FieldRange kJointDampingRatioRange{"joint_damping_ratio", 0.0, 10.0, "undamped"};
inline constexpr FieldRange kBacklashRange{"backlash_rad", 0.0, 1.0, "none"};  // rad
inline constexpr FieldRange kStribeckVelocityRange{"stribeck_velocity", 1e-5, 100.0,
                                                   "the plant's default"};  // rad/s
inline constexpr FieldRange kCoulombSmoothingRange{"coulomb_smoothing", 1e-5, 1.0,
                                                   "the plant's default"};  // rad/s
// The largest |coordinate| of a path's end points, m (RobotSetup::start_m, end_m): 1 km, beyond any
// robot's reach, so that what passes is finite in every later sum.
inline constexpr double kMaxPathCoordinateM = 1e3;
inline constexpr double kMinTickS = kTickMsRange.lo * 1e-3;
inline constexpr double kMaxTickS = kTickMsRange.hi * 1e-3;

// What real joints have beyond the paper's rigid, delay-free, ideally sensored joint (issue 29).
// Each field is a condition-file key and a sim_ab / rt_loop option of the same name (underscores
// -> dashes, e.g. plant_step_ms and --plant-step-ms); each is off by default, and a default
// JointEffects runs the plant bit for bit as without it. robot/plant.hpp gives the equations.
struct JointEffects {
  // plant_step_ms: the largest RK4 step of the plant, s (PlantConfig::substep_s and
  // coupled_substep_s); the plant's stiffness and motion bounds still apply, so a run with a step
  // ten times finer than the default checks that a result has converged. 0: the defaults (1 ms
  // decoupled, 50 ms coupled).
  double plant_step_s = 0.0;
  // delay_ms: time from sampling the joint to the torque reaching it, s (fractions of a tick
  // allowed; one tick is a digital drive's usual computation delay). At most 60 ticks.
  double delay_s = 0.0;
  // torque_bandwidth_hz: the current loop as a first-order lag on the applied torque, Hz
  // (0: ideal).
  double torque_bandwidth_hz = 0.0;
  // encoder_counts: the controller measures the angle quantised to 2π/N and the rate as the
  // difference of the last two readings over the tick (0: the true angle and rate).
  std::uint64_t encoder_counts = 0;
  // coulomb_nm, stribeck_nm (one number for every joint, or six): Coulomb friction C_i and the
  // Stribeck peak S_i of static friction (0 or below C_i: none), N·m at the joint, opposing its
  // velocity; stribeck_velocity: the Stribeck velocity v_s, rad/s (0: 0.01 rad/s).
  robot::JointVector coulomb_nm{};
  robot::JointVector stribeck_nm{};
  double stribeck_velocity_rad_s = 0.0;
  // coulomb_smoothing: the velocity v_ε over which the friction's sign is smoothed, rad/s (0: the
  // plant's 0.001 rad/s). The smoothed sign is the plant's stiffest term (the step rule takes
  // steps of about v_ε J / C), so a wider v_ε makes a run with friction much cheaper; it turns
  // stiction into a creep below about v_ε (robot/plant.hpp) -- a numerical compromise for
  // tuning, not a property of a joint.
  double coulomb_smoothing_rad_s = 0.0;
  // joint_resonance_hz (one number for every joint, or six; 0: rigid) and joint_damping_ratio:
  // an elastic gear as a two-mass joint, the motor side the armature (which must be > 0 there,
  // --armature), the link side the arm, the stiffness from the resonance and the two inertias at
  // the start. The controller measures the motor side (a motor encoder); trajectory.csv and the
  // metrics keep the link's angle.
  robot::JointVector joint_resonance_hz{};
  double joint_damping_ratio = 0.0;
  // backlash_rad: total play of the elastic gears, rad (needs joint_resonance_hz): no gear torque
  // while the deflection is within ±B/2.
  double backlash_rad = 0.0;

  [[nodiscard]] bool operator==(const JointEffects& o) const noexcept;
  [[nodiscard]] bool operator!=(const JointEffects& o) const noexcept { return !(*this == o); }
  // Empty, or what is wrong, naming the key.
  [[nodiscard]] std::string validate() const;
};

struct Condition {
  std::string name;
  std::string description;
  // Plant variant.
  double payload_scale = 1.0;         // link inertia x S (armature unchanged); controller unchanged
  double friction_per_s = 0.0;        // viscous b_i = B J^_i, N·m·s/rad
  double torque_limit_rad_s2 = 0.0;   // |tau_i| <= L J^_i (0: the URDF effort limits)
  double contact_rad_s2 = 0.0;        // amplitude of the deburring pulses (contact_pulses)
  double noise_position_rad = 0.0;    // std. dev. of Gaussian noise on measured angles
  double noise_velocity_rad_s = 0.0;  // std. dev. on measured velocities
  std::uint64_t seed = 1;             // noise seed
  // Path and start state.
  bool reverse = false;             // follow the path B -> A
  double initial_error_rad = 0.05;  // joints start this far behind the path (< 0: ahead), at rest
  // Robot, path and tick.
  RobotSetup robot;
  double payload_kg = 0.0;  // point mass at the tool flange, added to the plant's model only
  // The plant. These defaults are the paper's (for the bundled ER50-C20); the tools and condition
  // files give any other URDF default_dynamics() and default_gravity() instead.
  robot::PlantCoupling dynamics = robot::PlantCoupling::Decoupled;  // the paper's model
  bool gravity = false;  // rigid-body gravity (coupled dynamics only)
  JointEffects effects;  // what real joints have; none by default

  // Empty, or what is wrong (non-finite or out-of-range values).
  [[nodiscard]] std::string validate() const;
  [[nodiscard]] PulseTrain pulses() const noexcept { return contact_pulses(contact_rad_s2); }
};

// The plant a robot runs on unless told otherwise. The bundled ER50-C20 keeps the paper's model
// (decoupled joints, no gravity) so that the reproduction stays the paper's; any other URDF -- a
// user's arm, with the inertials every URDF here must have -- runs the coupled rigid-body dynamics
// with gravity, the plant its controller will meet: a controller tuned on the idealised plant can
// be unstable on the real one (docs/your_robot.md).
[[nodiscard]] robot::PlantCoupling default_dynamics(const RobotSetup& robot) noexcept;
// Gravity on by default where the plant is coupled and the robot is not the bundled ER50-C20.
[[nodiscard]] bool default_gravity(const RobotSetup& robot, robot::PlantCoupling dynamics) noexcept;

// The named scenarios in the order `--scenario all` runs them; "paper" first.
[[nodiscard]] const std::vector<Condition>& scenarios();
// nullptr when no scenario has that name.
[[nodiscard]] const Condition* find_scenario(const std::string& name);

}  // namespace fuzzypid::sim
