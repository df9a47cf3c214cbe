// What a controller file records of how `fuzzypid tune` found it (docs/tuning.md, the [tuning]
// table): the conditions and set it trained on, the search, the objective it minimised, the box
// and where the result sits in it, the files it trained on, the stages, the fuzzy-rules
// regulariser and, for a point of a front, its objectives. Plain data, no dependencies beyond the
// family names: controller_file/ reads and writes it, the tuner fills it.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "fuzzypid/controller/family.hpp"

namespace fuzzypid::tune {

// One searched parameter: name and its box in log10.
struct SearchBox {
  std::string name;
  double log10_min = 0.0;
  double log10_max = 0.0;
};

// A searched parameter that ended on (within 1 % of the width of) a side of its box: the optimum
// may lie outside it, and the box should be widened (`fuzzypid tune --box NAME=MIN:MAX`).
struct BoundHit {
  std::string name;
  bool upper = false;  // the box's maximum (true) or minimum (false)
  double log10 = 0.0;  // where the parameter ended
};

struct Objective {
  double overshoot_bound_pct = 20.0;  // overshoot above this is penalised (paper: 20 %)
  double overshoot_weight = 0.1;      // cost per percentage point above the bound, per joint
  double fault_cost = 1000.0;         // per run that faults, diverges or gives non-finite ITAE
  double divergence_rad = 1.0;        // |e| above this (any joint, any tick) counts as diverged
  // What a drive feels (tune/tune.hpp): cost per unit of each joint's command reversal share
  // (0..1) above chatter_limit_pct and of its RMS command relative to its limit (0..1), summed
  // over the joints. The defaults (300 above 5 %) are the smallest weight of 100, 300, 1000 (above
  // 5 %) with which each of the pid, scheduled and fuzzy families keeps every joint's reversals
  // at or below 10 % on the training and validation conditions of tuning/robust_drive.toml
  // (docs/tuning.md, "Chatter, chosen a third time"); a file without the key was tuned without
  // the term.
  double chatter_weight = 300.0;
  // Reversals up to this share (percent, 0..100) cost nothing: the term is chatter_weight x the
  // share above it. 0: every reversal costs (a file without the key).
  double chatter_limit_pct = 5.0;
  double effort_weight = 0.0;
  // Margins every candidate must keep (`fuzzypid tune --min-disk-margin` and the gain, phase and
  // delay forms; docs/margins.md): the worst frozen-gain margin over the joints and the training
  // conditions' plants (sim::certify). A candidate below any of them is infeasible: it is not
  // simulated and costs more than any feasible one. 0: no requirement.
  double min_disk_margin = 0.0;
  double min_gain_margin_db = 0.0;
  double min_phase_margin_deg = 0.0;
  double min_delay_margin_ms = 0.0;

  [[nodiscard]] bool requires_margins() const noexcept {
    return min_disk_margin > 0.0 || min_gain_margin_db > 0.0 || min_phase_margin_deg > 0.0 ||
           min_delay_margin_ms > 0.0;
  }
};

// A file a controller was tuned on: the condition file, or the URDF or path of a training
// condition, by name and a content hash (64-bit FNV-1a of the bytes, 16 hex digits), so a reader
// can tell whether the robot it runs is the one the gains were tuned for, and whether the
// condition file still is the one the tune read.
struct TrainedOn {
  std::string kind;     // "conditions", "urdf" or "path"
  std::string file;     // as the condition named it
  std::string fnv1a64;  // hex
};

// One stage of a staged tuning run.
struct StageRecord {
  controller::Family family{};
  std::uint64_t budget = 0;
  std::uint64_t evaluations = 0;
  double training_cost = 0.0;
  double validation_cost = std::numeric_limits<double>::quiet_NaN();  // NaN: no validation set
};

// One objective of a point of a front (`fuzzypid tune --objectives`, tune/front.hpp): its name
// and its value on the training conditions and on the validation ones (NaN: none held back).
struct FrontObjective {
  std::string name;
  double training = 0.0;
  double validation = std::numeric_limits<double>::quiet_NaN();
};

// How a fuzzy-rules table was kept readable and safe where training never goes.
struct TableRegulariser {
  std::string symmetry = "even";   // even | odd | none (kSymmetryNames)
  bool partition = false;          // were the set centers searched too
  double smoothness = 0.0;         // weight of the squared log10 differences of neighbouring cells
  double monotone = 0.0;           // weight of the squared violations of monotone rows and columns
  std::string unvisited = "seed";  // seed: cells training never visits keep the start's values
  double visit_threshold = 0.0;    // a cell is visited above this share of the firing weight
  std::uint64_t frozen_cells = 0;  // cells (of 49 per gain, summed) held at the start's values
  double cell_log10 = 0.0;         // each searched cell's box: log10 ratio in [-cell_log10, +]
};

struct Tuning {
  std::string conditions;  // the conditions file, as given to `fuzzypid tune`
  std::string set;         // the training set's name
  std::string algorithm;   // e.g. "pagmo::sade"
  std::uint64_t budget = 0;
  std::uint64_t evaluations = 0;
  std::uint64_t seed = 0;
  std::uint64_t threads = 0;
  std::uint64_t population = 0;
  double training_cost = 0.0;
  Objective objective{};
  std::vector<SearchBox> box;
  std::vector<BoundHit> on_bound;     // parameters of the result on a side of `box`
  std::vector<TrainedOn> trained_on;  // empty: the bundled ER50-C20 on the section 6 line
  // The controller tick of the training conditions, s (0: not recorded, or they differ).
  double tick_s = 0.0;
  // Staged tuning (`fuzzypid tune --init`, `--stages`): the controller file the search started
  // from ("" for none), the stages run (family, evaluations, costs) and the validation conditions
  // held back from the training set that chose among them (0: none; the cost is then NaN).
  std::string init;
  std::vector<StageRecord> stages;
  std::uint64_t validation_conditions = 0;
  double validation_cost = std::numeric_limits<double>::quiet_NaN();
  std::optional<TableRegulariser> regulariser;  // fuzzy-rules only
  std::vector<FrontObjective> front;            // a point of a front: its objectives
};

}  // namespace fuzzypid::tune
