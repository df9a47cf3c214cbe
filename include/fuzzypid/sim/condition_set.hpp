// Condition sets: named lists of conditions in a TOML file (tuning/robust.toml), e.g. a training
// set for `fuzzypid tune` and a held-out set that only sim_ab evaluates.
//
//   [sets.NAME]
//   description = "..."                       # optional
//   conditions = [                            # optional
//     { name = "light-ahead", payload_scale = 0.5, initial_error = -0.05 },
//     { name = "contact", scenario = "deburring" },   # a named scenario, fields override it
//   ]
//   [sets.NAME.monte_carlo]                   # optional: N seeded random draws
//   count = 20
//   seed = 7
//   payload_scale = [0.5, 2.0]                # drawn log-uniformly in [min, max]
//   friction = [0.0, 2.0]                     # uniformly
//   initial_error = [-0.08, 0.08]             # uniformly
//   payload_kg = [0.0, 5.0]                   # uniformly; so are the keys of what real joints
//   delay_ms = [0.0, 10.0]                    # have given as [min, max] (one value for every
//   encoder_counts = [4096, 65536]            # joint; counts rounded), and a number sets them
// The draws of payload_kg and the joint keys come from a stream of their own (one draw per key and
// condition, in a fixed order), so adding one changes neither the others nor the three above.
//   sampling = "latin-hypercube"              # optional (default "random"): each range cut into
//                                             # count equally likely strata, one draw in each
// With "latin-hypercube" each draw keeps its place within its stratum from the same streams, and
// the order of the strata comes from a stream of its own: "random" draws stay as they always were.
//
// Condition keys: name, description, scenario, payload_scale, friction, torque_limit, contact,
// noise = [SIGMA_Q, SIGMA_QD], seed, reverse, initial_error (sim_ab's options of the same names).
//
// The robot, path and plant of a condition (sim_ab's --urdf, --base-link, --tip-link, --path,
// --tick-ms, --payload-kg, --armature, --dynamics, --gravity):
//   urdf = "ur5.urdf"          base_link = "base_link"     tip_link = "tool0"
//   path = "contour.csv"       tick_ms = 10.0              payload_kg = 2.5
//   armature = [A1, A2, A3, A4, A5, A6]                    (kg·m²; default: see RobotSetup)
//   ik_seed = [Q1, Q2, Q3, Q4, Q5, Q6]                     (rad; first IK of a Cartesian path)
//   dynamics = "decoupled" | "coupled"                     gravity = true (coupled only)
// What real joints have (sim::JointEffects; sim_ab's and rt_loop's options of the same names; each
// 0 = off):
//   plant_step_ms = 0.1        (largest plant integration step, ms)
//   delay_ms = 10.0            (sampling to torque, ms)    torque_bandwidth_hz = 200.0
//   encoder_counts = 131072    (per revolution, integer)
//   coulomb_nm = 20.0 | [C1, ..., C6]   stribeck_nm = 30.0 | [S1, ..., S6]   (N·m)
//   stribeck_velocity = 0.01   (rad/s)     coulomb_smoothing = 0.02   (rad/s; default 0.001)
//   joint_resonance_hz = 20.0 | [F1, ..., F6]   joint_damping_ratio = 0.05   (two-mass gear)
//   backlash_rad = 0.001       (play of the elastic gears, rad)
// Relative file names resolve against the condition file's folder. Given in a set's table (next
// to `description`), they are the defaults of every condition of that set, Monte-Carlo draws
// included; a condition's own keys override them.
// Unknown keys, wrong types, NaN and out-of-range values are errors with file:line:column.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "fuzzypid/controller/controller_spec.hpp"
#include "fuzzypid/enum_names.hpp"
#include "fuzzypid/file_error.hpp"
#include "fuzzypid/sim/condition.hpp"

namespace fuzzypid::sim {

inline constexpr std::array<fuzzypid::EnumName<robot::PlantCoupling>, 2> kDynamicsNames{
    {{robot::PlantCoupling::Decoupled, "decoupled"}, {robot::PlantCoupling::Coupled, "coupled"}}};

// How a Monte-Carlo table spreads its draws over each range (key `sampling`).
enum class Sampling : std::uint8_t {
  // Each draw independent and uniform: N draws can leave a range's end unvisited.
  Random,
  // Latin hypercube: each range cut into N equally likely strata, each stratum drawn exactly once
  // (in a seeded random order per key, at a seeded random place within it).
  LatinHypercube,
};
inline constexpr std::array<fuzzypid::EnumName<Sampling>, 2> kSamplingNames{
    {{Sampling::Random, "random"}, {Sampling::LatinHypercube, "latin-hypercube"}}};

struct ConditionSet {
  std::string name;
  std::string description;
  std::vector<Condition> conditions;  // listed ones first, then the Monte-Carlo draws
};

struct ConditionFile {
  std::string path;
  std::vector<ConditionSet> sets;  // in name order
  [[nodiscard]] const ConditionSet* find(const std::string& name) const;
  [[nodiscard]] std::string set_names() const;  // "a, b"
};

[[nodiscard]] bool parse_conditions(std::string_view text, const std::string& source,
                                    ConditionFile& file, fuzzypid::FileError& error);
[[nodiscard]] bool load_conditions(const std::string& path, ConditionFile& file,
                                   fuzzypid::FileError& error);

}  // namespace fuzzypid::sim
