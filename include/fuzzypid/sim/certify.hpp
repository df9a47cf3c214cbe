// Frozen-gain certification of a six-joint controller over the conditions it will run on
// (docs/margins.md; `fuzzypid certify`).
//
// For each joint i, the linear loop of margins.hpp is evaluated over
//   - the inertia range [J_min, J_max]: J_i = s M_ii(q) + J_motor,i at every sample of every
//     condition's planned path (s the condition's payload_scale, M_ii the diagonal of the mass
//     matrix of the condition's plant model, payload at the flange included; J_motor the armature),
//     evaluated at J_min, their geometric mean and J_max;
//   - the viscous friction range [b_min, b_max], b_i = friction_per_s J^_i of each condition;
//   - each condition's elastic gear (joint_resonance_hz, joint_damping_ratio; margins.hpp): its
//     stiffness and damping as robot::JointPlant fixes them at reset(), the motor's share and the
//     resonance following at each evaluated inertia, at the options' delay and at the condition's
//     own (frozen-gain margins only: the common Lyapunov function below is of the rigid joint);
//   - every controller tick the conditions run at, and the extra delay of the options (any
//     value: whole ticks and a fraction, margins.hpp);
//   - the gain triples the controller can produce: its gains for a PID; for a moving-gain family
//     (scheduled, fuzzy, fuzzy-rules) the gains its own supervisor returns over a grid of the scaled
//     inputs (x, y) = (Ke e, Kec ec) in [−8, 8]² (denser within [−1, 1]), computed by
//     controller::JointControllers from a fresh start (for GainUpdate::Incremental: one tick from
//     K0, not the set reachable over many ticks).
// The worst case of each margin and where it occurs are reported. Frozen-gain margins do not carry
// over to gains that change every tick unless they change slowly (Shamma and Athans, 1991), so
// each joint also gets the certificate of lyapunov.hpp: one quadratic Lyapunov function common to
// every corner of the box of the gain triples above (for GainUpdate::Incremental the gain bounds
// of the file, which that update can reach) × the plant-gain and damping ranges of each group of
// plants (tick, J^, current loop). A controller is "certified" when every loop is stable at frozen
// gains with a positive disk margin and every joint has that certificate: then no sequence of
// gains the supervisor can produce, switching on every tick, and no variation of the inertia
// within its range destabilises the linear loop (lyapunov_assumptions()).
//
// Part of fuzzypid::sim (set-up code: allocates, reports errors).
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "fuzzypid/controller/controller_spec.hpp"
#include "fuzzypid/controller/margin_record.hpp"
#include "fuzzypid/pid/gains.hpp"
#include "fuzzypid/sim/condition.hpp"
#include "fuzzypid/sim/experiment.hpp"
#include "fuzzypid/sim/lyapunov.hpp"
#include "fuzzypid/sim/margins.hpp"

namespace fuzzypid::sim {

struct CertifyOptions {
  double delay_s = 0.0;          // extra delay, s, >= 0 (whole ticks and a fraction)
  std::size_t grid_points = 25;  // per axis of the (x, y) grid of moving-gain families, >= 3
  MarginOptions margin{};
  bool lyapunov = true;  // also solve for the common Lyapunov function (SDPA)
  // Runs `joint(i)` once for each i in [0, n); empty: in order on this thread. Each call touches
  // only joint i's part of the certificate, so a caller may run them in parallel (the tuner's
  // screening does, on its threads); the certificate is the same either way. With `lyapunov` the
  // calls also run the SDPA solver: give an executor only without it.
  std::function<void(std::size_t n, const std::function<void(std::size_t)>& joint)> for_each_joint;
};

// One evaluated loop and where it comes from.
struct MarginCase {
  LoopMargins margins{};
  JointLoop loop{};  // the loop the margins are of
  double inertia_kgm2 = 0.0;
  double damping_nms = 0.0;
  double tick_s = 0.0;
  pid::Gains<double> gains{};  // continuous SI form
  double x = 0.0, y = 0.0;     // scaled inputs that produced the gains (0, 0 for a PID)
};

struct JointCertificate {
  double nominal_inertia_kgm2 = 0.0;  // J^ of the controller (largest over the conditions)
  double inertia_min_kgm2 = 0.0, inertia_max_kgm2 = 0.0;
  double damping_min_nms = 0.0, damping_max_nms = 0.0;
  std::size_t gain_triples = 0;  // distinct gain triples evaluated
  std::size_t cases = 0;         // loops evaluated
  bool stable = false;           // every evaluated loop stable
  // The worst case of each margin (lowest upper gain margin, highest lower gain margin, lowest
  // phase, delay and disk margins). Only worst_delay has delay_margin_ticks and
  // delay_margin_exact_s (they take eigenvalues of growing loops): those of the case with the
  // lowest allmargin delay margin.
  MarginCase worst_gain, worst_gain_low, worst_phase, worst_delay, worst_disk;
  // The box of the gain triples (continuous SI form) and its certificate: the worst over the
  // plant groups (the first that fails, else the largest contraction). Not computed (reason
  // "not computed") when CertifyOptions::lyapunov is false.
  GainBox gain_box{};
  LyapunovCertificate lyapunov{};
  std::size_t plant_groups = 0;
  // Stable at every evaluated loop with a positive disk margin, and the certificate above.
  bool certified = false;
};

struct Certificate {
  controller::Family family{};
  bool moving_gains = false;
  double delay_s = 0.0;
  std::size_t conditions = 0;
  std::array<JointCertificate, robot::kNumJoints> joints{};
  bool certified = false;
  std::string verdict;  // "certified (linear, no saturation)" or "not certified (...)"
};

// The smallest of each margin over the joints (the controller's worst case), as controller files
// record them and `fuzzypid tune --min-*` constrains them.
struct MarginSummary {
  double gain_margin_db = 0.0;
  double phase_margin_deg = 0.0;
  double delay_margin_ms = 0.0;
  double disk_margin = 0.0;
};
[[nodiscard]] MarginSummary summarize(const Certificate& cert);

// The record a controller file keeps of `cert` (its conditions and set left empty).
[[nodiscard]] controller::MarginRecord margin_record(const Certificate& cert);

// The delay certify assumes for a set of conditions: the largest of their delay_s, s (0: none).
[[nodiscard]] double largest_delay_s(const std::vector<Condition>& conditions) noexcept;

// The plants one joint meets at one tick, one nominal inertia J^, one current loop and one gear:
// the ranges of its effective inertia and viscous friction over the conditions.
struct PlantGroup {
  double tick_s = 0.0;
  double nominal_inertia_kgm2 = 0.0;
  double torque_bandwidth_hz = 0.0;
  double inertia_min = 0.0, inertia_max = 0.0;  // kg·m²
  double damping_min = 0.0, damping_max = 0.0;  // N·m·s/rad
  // An elastic gear (robot::PlantConfig::joint_resonance_hz): its stiffness (N·m/rad; 0: a rigid
  // joint) and damping (N·m·s/rad) as the plant fixes them at reset(), and the motor side's
  // inertia (the armature, kg·m²). At an inertia J the loop's motor share is J_m / J and its
  // resonance √(k (1/J_m + 1/(J − J_m))).
  double gear_stiffness_nm_per_rad = 0.0;
  double gear_damping_nms = 0.0;
  double motor_inertia_kgm2 = 0.0;
  // With a gear, the condition's own delay (s): a gear near the Nyquist rate can be stable behind
  // a whole tick and unstable behind less, so such a group is evaluated at this delay as well as
  // at CertifyOptions::delay_s. 0 for a rigid joint.
  double delay_s = 0.0;
};

struct PlantRanges {
  std::array<std::vector<PlantGroup>, robot::kNumJoints> joints;
  std::size_t conditions = 0;
};

// The plant groups of `conditions` (conditions[k] runs on experiments[k]). Returns nullopt with
// `error` set when there are none or a path cannot be planned. Computed once, it serves any number
// of controllers (the tuner certifies every candidate against it).
[[nodiscard]] std::optional<PlantRanges> plant_ranges(
    const std::vector<Condition>& conditions, const std::vector<const Experiment*>& experiments,
    std::string& error);

// Certifies `controller` on the plants of `ranges`. Returns nullopt with `error` set when the
// delay is negative or not finite, or the controller cannot be built.
[[nodiscard]] std::optional<Certificate> certify(const ControllerSpec& controller,
                                                 const PlantRanges& ranges,
                                                 const CertifyOptions& options, std::string& error);

// Both steps: certifies `controller` on `conditions` (each run by `experiments.of(k)`).
[[nodiscard]] std::optional<Certificate> certify(const ControllerSpec& controller,
                                                 const std::vector<Condition>& conditions,
                                                 const ExperimentSet& experiments,
                                                 const CertifyOptions& options, std::string& error);

}  // namespace fuzzypid::sim
