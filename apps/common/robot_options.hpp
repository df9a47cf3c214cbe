// The robot, path and plant options shared by sim_ab and rt_loop (CLI11), with the ranges of
// sim/condition.hpp (the condition files use the same ones):
//   --urdf FILE --base-link NAME --tip-link NAME --path FILE --tick-ms T --armature A1,...,A6
//   --ik-seed Q1,...,Q6 --payload-kg M --dynamics decoupled|coupled --gravity
// and what real joints have (sim::JointEffects): --plant-step-ms S --delay-ms D
//   --torque-bandwidth-hz F --encoder-counts N --coulomb-nm C --stribeck-nm S --stribeck-velocity V
//   --joint-resonance-hz F --joint-damping-ratio Z --backlash-rad B
// Header-only: included by the tools that link fuzzypid::sim and fuzzypid::controller_file.
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <set>
#include <sstream>
#include <string>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid/robot/plant.hpp"
#include "fuzzypid/robot/robot_model.hpp"
#include "fuzzypid/sim/condition.hpp"
#include "fuzzypid/sim/condition_set.hpp"
#include "fuzzypid/sim/experiment.hpp"

namespace fuzzypid::cli {

struct RobotOptions {
  sim::RobotSetup setup;  // --urdf, --base-link, --tip-link, --path, --tick-ms, --armature, ...
  std::optional<double> payload_kg;
  // Unset: the robot's default (sim::default_dynamics, sim::default_gravity).
  std::optional<robot::PlantCoupling> dynamics;
  std::optional<bool> gravity;
  bool tick_given = false;
  sim::JointEffects effects;  // --plant-step-ms, ... (what real joints have)

  // Whether any option naming the robot, its path or its plant was given.
  [[nodiscard]] bool any() const {
    return !setup.urdf.empty() || !setup.base_link.empty() || !setup.tip_link.empty() ||
           !setup.path.empty() || tick_given || setup.armature_kgm2 || setup.ik_seed_rad ||
           payload_kg || dynamics || gravity.has_value() || effects != sim::JointEffects{};
  }
  // The options applied to a condition.
  void apply(sim::Condition& c) const {
    c.robot.urdf = setup.urdf;
    c.robot.base_link = setup.base_link;
    c.robot.tip_link = setup.tip_link;
    c.robot.path = setup.path;
    if (tick_given) c.robot.tick_s = setup.tick_s;
    c.robot.armature_kgm2 = setup.armature_kgm2;
    c.robot.ik_seed_rad = setup.ik_seed_rad;
    if (payload_kg) c.payload_kg = *payload_kg;
    c.dynamics = dynamics.value_or(sim::default_dynamics(c.robot));
    c.gravity = gravity.value_or(sim::default_gravity(c.robot, c.dynamics));
    c.effects = effects;
  }
};

// An option of JointEffects: "--" + the range's key with '_' -> '-', in the range's units, 0
// (range.zero: off, or the plant's default) or within the range; stored times `to_si`.
inline void add_effect_option(CLI::App& app, const sim::FieldRange& range, double to_si,
                              double& target, const std::string& help, const std::string& text) {
  std::string name = std::string("--") + range.key;
  for (char& ch : name)
    if (ch == '_') ch = '-';
  app.add_option_function<std::string>(
         name,
         [name, range, to_si, &target](const std::string& s) {
           const auto v = parse_finite(s);
           if (!v || (*v != 0.0 && !range.contains(*v)))
             throw CLI::ValidationError(name, std::string("expected 0 (") + range.zero +
                                                  ") or a number within " +
                                                  CLI::detail::to_string(range.lo) + " .. " +
                                                  CLI::detail::to_string(range.hi) + ": " + s);
           target = *v * to_si;
         },
         help)
      ->option_text(text);
}

// "a,b,c,d,e,f": six finite numbers.
inline bool parse_six(const std::string& text, robot::JointVector& out) {
  std::stringstream in(text);
  std::string field;
  std::size_t k = 0;
  while (std::getline(in, field, ',')) {
    if (k == out.size()) return false;
    const auto v = parse_finite(field);
    if (!v) return false;
    out[k++] = *v;
  }
  return k == out.size() && !text.empty() && text.back() != ',';
}

// A per-joint option of JointEffects: one number for every joint or six, each within the range.
inline void add_joint_effect_option(CLI::App& app, const sim::FieldRange& range,
                                    robot::JointVector& target, const std::string& help,
                                    const std::string& text) {
  std::string name = std::string("--") + range.key;
  for (char& ch : name)
    if (ch == '_') ch = '-';
  app.add_option_function<std::string>(
         name,
         [name, range, &target](const std::string& s) {
           robot::JointVector v{};
           if (const auto one = parse_finite(s)) {
             v.fill(*one);
           } else if (!parse_six(s, v)) {
             throw CLI::ValidationError(name, "expected one number or 6 comma-separated: " + s);
           }
           for (double x : v)
             if (!range.contains(x))
               throw CLI::ValidationError(name, "values must be within " +
                                                    CLI::detail::to_string(range.lo) + " .. " +
                                                    CLI::detail::to_string(range.hi) + ": " + s);
           target = v;
         },
         help)
      ->option_text(text);
}

// Adds the options; `with_tick` adds --tick-ms (rt_loop has its own period and dt options).
inline void add_robot_options(CLI::App& app, RobotOptions& o, bool with_tick) {
  const auto path_check = [](const std::string& s) -> std::string {
    return s.empty() ? "empty file name" : "";
  };
  app.add_option("--urdf", o.setup.urdf,
                 "robot description: a URDF with a serial chain of exactly 6 revolute or "
                 "continuous joints between base and tip, each with <limit> (lower/upper for "
                 "revolute, velocity, effort) and <inertial> on the moving links (default: the "
                 "bundled ER50-C20)")
      ->check(path_check)
      ->option_text("FILE");
  app.add_option("--base-link", o.setup.base_link, "first link of the chain (default: the root)")
      ->option_text("NAME");
  app.add_option("--tip-link", o.setup.tip_link,
                 "last link of the chain, the tool flange (default: the end of the unique chain)")
      ->option_text("NAME");
  app.add_option("--path", o.setup.path,
                 "path CSV with header t_s,q1_rad,...,q6_rad (joint samples) or "
                 "t_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad (tool poses in the base frame, "
                 "URDF fixed-axis RPY); interpolated at the tick by cubic Hermite (default: the "
                 "paper's line A -> B)")
      ->check(path_check)
      ->option_text("FILE");
  if (with_tick)
    app.add_option_function<double>(
           "--tick-ms",
           [&o](double ms) {
             o.setup.tick_s = ms * 1e-3;
             o.tick_given = true;
           },
           "controller tick, ms (default 50)")
        ->check(finite_in(sim::kTickMsRange.lo, sim::kTickMsRange.hi))
        ->option_text("T");
  app.add_option_function<std::string>(
         "--armature",
         [&o](const std::string& s) {
           robot::JointVector v{};
           if (!parse_six(s, v))
             throw CLI::ValidationError("--armature",
                                        "expected 6 comma-separated numbers (kg·m²): " + s);
           for (double a : v)
             if (!sim::kArmatureRange.contains(a))
               throw CLI::ValidationError(
                   "--armature", "values must be within " + sim::kArmatureRange.text() + ": " + s);
           o.setup.armature_kgm2 = v;
         },
         "reflected motor inertia of each joint, kg·m² (default: the ER50's estimates for the "
         "bundled ER50-C20, 0 for any other URDF)")
      ->option_text("A1,...,A6");
  app.add_option_function<std::string>(
         "--ik-seed",
         [&o](const std::string& s) {
           robot::JointVector v{};
           if (!parse_six(s, v))
             throw CLI::ValidationError("--ik-seed", "expected 6 comma-separated angles: " + s);
           o.setup.ik_seed_rad = v;
         },
         "joint angles seeding the first inverse kinematics of a Cartesian path, rad (default: "
         "the middle of each joint's limits)")
      ->option_text("Q1,...,Q6");
  app.add_option_function<double>(
         "--payload-kg", [&o](double m) { o.payload_kg = m; },
         "point mass at the tool flange, kg (the controller's model keeps none)")
      ->check(finite_in(sim::kPayloadKgRange.lo, sim::kPayloadKgRange.hi))
      ->option_text("M");
  std::vector<std::string> names;
  names.reserve(sim::kDynamicsNames.size());
  for (const auto& e : sim::kDynamicsNames)
    names.emplace_back(e.name);
  app.add_option_function<std::string>(
         "--dynamics",
         [&o](const std::string& s) { o.dynamics = *fuzzypid::parse_enum(sim::kDynamicsNames, s); },
         "plant: decoupled joints J_i theta'' = tau (the paper's model; the default for the "
         "bundled ER50-C20) or coupled rigid-body dynamics M(q) q'' + C q' + g = tau (the "
         "default for any other URDF)")
      ->check(CLI::IsMember(names));
  app.add_flag_function(
      "--gravity,!--no-gravity", [&o](std::int64_t n) { o.gravity = n > 0; },
      "gravity in the plant (needs the coupled dynamics; default: on for a coupled plant of any "
      "URDF but the bundled ER50-C20)");
  add_effect_option(app, sim::kPlantStepMsRange, 1e-3, o.effects.plant_step_s,
                    "largest integration step of the plant, ms (default: 1 ms decoupled, 50 ms "
                    "coupled, shorter where friction, the current loop or the gear is stiff)",
                    "S");
  add_effect_option(app, sim::kDelayMsRange, 1e-3, o.effects.delay_s,
                    "time from sampling the joint to the torque reaching it, ms (fractions of a "
                    "tick allowed; default 0)",
                    "D");
  add_effect_option(app, sim::kTorqueBandwidthRange, 1.0, o.effects.torque_bandwidth_hz,
                    "current loop as a first-order lag on the torque, Hz (default 0: ideal)", "F");
  app.add_option_function<std::string>(
         "--encoder-counts",
         [&o](const std::string& s) {
           const auto n = parse_unsigned(s);
           if (!n || (*n != 0 && !sim::kEncoderCountsRange.contains(static_cast<double>(*n))))
             throw CLI::ValidationError(
                 "--encoder-counts", std::string("expected 0 (") + sim::kEncoderCountsRange.zero +
                                         ") or an integer within " +
                                         sim::kEncoderCountsRange.text() + ": " + s);
           o.effects.encoder_counts = *n;
         },
         "the measured angle quantised to 2 pi/N, the rate differenced from it (default 0: exact)")
      ->option_text("N");
  add_joint_effect_option(app, sim::kCoulombRange, o.effects.coulomb_nm,
                          "Coulomb friction at each joint, N·m (default 0)", "C|C1,...,C6");
  add_joint_effect_option(app, sim::kStribeckRange, o.effects.stribeck_nm,
                          "Stribeck peak of static friction, N·m (default 0: none)", "S|S1,...,S6");
  add_effect_option(app, sim::kStribeckVelocityRange, 1.0, o.effects.stribeck_velocity_rad_s,
                    "Stribeck velocity, rad/s (default 0.01)", "V");
  add_effect_option(app, sim::kCoulombSmoothingRange, 1.0, o.effects.coulomb_smoothing_rad_s,
                    "velocity over which the friction's sign is smoothed, rad/s (default 0.001; "
                    "wider: cheaper runs, creep instead of stiction)",
                    "V");
  add_joint_effect_option(app, sim::kJointResonanceRange, o.effects.joint_resonance_hz,
                          "gear resonance of a two-mass joint, Hz (needs an armature; the drive "
                          "measures the motor side; default 0: rigid)",
                          "F|F1,...,F6");
  add_effect_option(app, sim::kJointDampingRatioRange, 1.0, o.effects.joint_damping_ratio,
                    "damping ratio of the gear resonance (default 0)", "Z");
  add_effect_option(app, sim::kBacklashRange, 1.0, o.effects.backlash_rad,
                    "play of the elastic gears, rad (needs --joint-resonance-hz; default 0)", "B");
}

// Usage errors the options can have on their own; empty when none.
inline std::string check_robot_options(const RobotOptions& o) {
  const robot::PlantCoupling dynamics = o.dynamics.value_or(sim::default_dynamics(o.setup));
  if (o.gravity.value_or(false) && dynamics != robot::PlantCoupling::Coupled)
    return o.dynamics ? "--gravity needs --dynamics coupled"
                      : "--gravity needs --dynamics coupled (the bundled ER50-C20 runs the paper's "
                        "decoupled plant by default)";
  // The built-in line has its own start joints; only a Cartesian path file's first row is seeded.
  if (o.setup.ik_seed_rad && o.setup.path.empty())
    return "--ik-seed applies only to a Cartesian path file; without --path the built-in line "
           "A -> B runs from its own start joints";
  return {};
}

// What a run used, for stderr: the URDF, the path and the armature.
inline void print_robot_note(const char* tool, const sim::Experiment& ex) {
  const auto& a = ex.armature_kgm2();
  std::fprintf(
      stderr, "%s: robot %s (%s -> %s), path %s, tick %g ms, armature %g,%g,%g,%g,%g,%g kg·m²\n",
      tool, ex.urdf_file().c_str(), ex.model().root_link().c_str(), ex.model().tip_link().c_str(),
      ex.setup().path.empty() ? "the section 6 line A -> B" : ex.setup().path.c_str(),
      ex.options().tick_s * 1e3, a[0], a[1], a[2], a[3], a[4], a[5]);
}

// The plant a condition runs on, for the banner: "dynamics coupled, gravity on, payload 2 kg".
inline std::string plant_note(const sim::Condition& c) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "dynamics %s, gravity %s, payload %g kg",
                fuzzypid::name_of(sim::kDynamicsNames, c.dynamics), c.gravity ? "on" : "off",
                c.payload_kg);
  std::string note = buf;
  // What real joints have, where set (the largest joint's value for the per-joint keys).
  const sim::JointEffects& e = c.effects;
  const auto add = [&note](const char* what, double v, const char* unit) {
    if (v == 0.0) return;
    char b[96];
    std::snprintf(b, sizeof b, ", %s %g%s", what, v, unit);
    note += b;
  };
  const auto largest = [](const robot::JointVector& v) {
    double m = 0.0;
    for (double x : v)
      m = x > m ? x : m;
    return m;
  };
  add("plant step", e.plant_step_s * 1e3, " ms");
  add("delay", e.delay_s * 1e3, " ms");
  add("current loop", e.torque_bandwidth_hz, " Hz");
  add("encoder", static_cast<double>(e.encoder_counts), " counts");
  add("Coulomb up to", largest(e.coulomb_nm), " N·m");
  add("Stribeck up to", largest(e.stribeck_nm), " N·m");
  add("gear resonance up to", largest(e.joint_resonance_hz), " Hz");
  add("backlash", e.backlash_rad, " rad");
  return note;
}

// Says `text` on stderr as "TOOL: KIND: text" once per process (a tool meets the same robot in
// many conditions): for inputs that are legal but probably not what the user meant.
inline void say_once(const char* tool, const char* kind, const std::string& text) {
  static std::set<std::string> said;
  if (said.insert(text).second) std::fprintf(stderr, "%s: %s: %s\n", tool, kind, text.c_str());
}

// What the URDF leaves open (a limit of 0 means none), once per joint and URDF.
inline void print_model_notes(const char* tool, const sim::Experiment& ex) {
  for (const std::string& note : ex.model().notes())
    say_once(tool, "note", ex.urdf_file() + ": " + note);
}

// A payload heavier than the arm's own moving links is legal but rarely meant (grams read as kg,
// or the whole robot's mass from a data sheet).
inline void warn_about_payload(const char* tool, const sim::Experiment& ex,
                               const sim::Condition& c) {
  const double arm_kg = ex.model().moving_mass_kg();
  if (!(c.payload_kg > arm_kg)) return;
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "condition %s: payload %g kg is above the arm's own moving mass %g kg (the links "
                "of %s below its first joint): is it meant?",
                c.name.c_str(), c.payload_kg, arm_kg, ex.urdf_file().c_str());
  say_once(tool, "warning", buf);
}

// A controller file run on another robot or path than its tuning record names (tuning.trained_on):
// the gains were fitted to other inertias, so its quality is not the recorded one.
inline void warn_about_training(const char* tool, const std::string& controller_path,
                                const tune::Tuning* tuning, const sim::Experiment& ex) {
  for (const std::string& d : controller_file::trained_on_differences(
           tuning, controller_path, ex.urdf_file(), ex.setup().path, robot::default_urdf_path()))
    say_once(tool, "warning",
             "controller " + controller_path + " runs on another robot or path than it was " +
                 "tuned on: " + d);
}

// A controller file run on the condition file it was tuned on, after that file changed.
inline void warn_about_conditions(const char* tool, const std::string& controller_path,
                                  const tune::Tuning* tuning, const std::string& conditions) {
  const std::string d = controller_file::conditions_changed(tuning, controller_path, conditions);
  if (!d.empty()) say_once(tool, "warning", "controller " + controller_path + " was " + d);
}

}  // namespace fuzzypid::cli
