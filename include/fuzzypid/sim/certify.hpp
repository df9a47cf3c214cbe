// Frozen-gain certification of a six-joint controller over the conditions it will run on
// (docs/margins.md; `fuzzypid certify`).
//
// For each joint i, the linear loop of margins.hpp is evaluated over
//   - the inertia range [J_min, J_max]: J_i = s M_ii(q) + J_motor,i at every sample of every
//     condition's planned path (s the condition's payload_scale, M_ii the diagonal of the mass
//     matrix of the condition's plant model, payload at the flange included; J_motor the armature),
//     evaluated at J_min, their geometric mean and J_max;
//   - the viscous friction range [b_min, b_max], b_i = friction_per_s J^_i of each condition;
//   - every controller tick the conditions run at, and the extra delay of the options (any
//     value: whole ticks and a fraction, margins.hpp);
//   - the gain triples the controller can produce: its gains for a PID; for a moving-gain family
//     (scheduled, fuzzy, fuzzy-rules) the gains its own supervisor returns over a grid of the scaled
//     inputs (x, y) = (Ke e, Kec ec) in [−8, 8]² (denser within [−1, 1]), computed by
//     controller::JointControllers from a fresh start (for GainUpdate::Incremental: one tick from
//     K0, not the set reachable over many ticks).
// The worst case of each margin and where it occurs are reported. A fixed PID whose loop is stable
// with a positive disk margin everywhere is "certified (linear, no saturation)"; a moving-gain
// controller is at best "not certified (frozen-gain margins only)": frozen-gain margins do not
// carry over to gains that change every tick unless they change slowly (Shamma and Athans, 1991).
//
// Part of fuzzypid::sim (set-up code: allocates, reports errors).
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "fuzzypid/controller/controller_spec.hpp"
#include "fuzzypid/pid/gains.hpp"
#include "fuzzypid/sim/condition.hpp"
#include "fuzzypid/sim/experiment.hpp"
#include "fuzzypid/sim/margins.hpp"

namespace fuzzypid::sim {

struct CertifyOptions {
  double delay_s = 0.0;          // extra delay, s, >= 0 (whole ticks and a fraction)
  std::size_t grid_points = 25;  // per axis of the (x, y) grid of moving-gain families, >= 3
  MarginOptions margin{};
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
};

struct Certificate {
  controller::Family family = controller::Family::Pid;
  bool moving_gains = false;
  double delay_s = 0.0;
  std::size_t conditions = 0;
  std::array<JointCertificate, robot::kNumJoints> joints{};
  bool certified = false;
  std::string verdict;  // "certified (linear, no saturation)" or "not certified (...)"
};

// Certifies `controller` on `conditions` (each run by `experiments.of(k)`). Returns nullopt with
// `error` set when a path cannot be planned, the delay is negative or not finite, or the
// controller cannot be built.
[[nodiscard]] std::optional<Certificate> certify(const ControllerSpec& controller,
                                                 const std::vector<Condition>& conditions,
                                                 const ExperimentSet& experiments,
                                                 const CertifyOptions& options, std::string& error);

}  // namespace fuzzypid::sim
