// Multi-objective tuning: the Pareto front of a controller family over objectives in tension
// (docs/tuning.md, "Fronts"), found by pagmo2's NSGA-II under the same hard budget, boxes,
// training and validation conditions as the one-objective tuner (tune.hpp).
//
// Every objective is minimised. Over the runs of a condition set, with F = fault_cost x the runs
// that fault (diverge, leave their limits or give a non-finite metric; such a run adds F and
// nothing else):
//   itae       the summed ITAE of the joints, rad·s², + F
//   effort     the mean over runs and joints of rms(u) / u_limit (0 .. 1), + F
//   chatter    the mean over runs and joints of the command's reversal share, % (sim::reversals_pct,
//              as metrics.csv reports it), + F
//   overshoot  the mean over runs and joints of the overshoot, % (relative to the travel on a
//              closed contour), + F
//   margin     −alpha: the worst frozen-gain disk margin over the joints and the set's plants
//              (sim::certify with the tuner's screening options), negated; + F
// and the regulariser's penalty of a fuzzy-rules table (0 by default) is added to each.
//
// The search is resumable: its whole state after a generation is a FrontState (the generation
// and the population's points and objectives), and generation g's offspring depend only on that
// state and (seed, g), so a search stopped after any generation and resumed from its state ends
// exactly where an uninterrupted one ends.
//
// Library fuzzypid::tune (offline, allocates, never in a control loop).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "fuzzypid/enum_names.hpp"
#include "fuzzypid/tune/tune.hpp"

namespace fuzzypid::tune {

enum class Metric : std::uint8_t { Itae, Effort, Chatter, Overshoot, Margin };
inline constexpr std::array<EnumName<Metric>, 5> kMetricNames{{{Metric::Itae, "itae"},
                                                               {Metric::Effort, "effort"},
                                                               {Metric::Chatter, "chatter"},
                                                               {Metric::Overshoot, "overshoot"},
                                                               {Metric::Margin, "margin"}}};

// The search after a generation: every member's point (log10, box order) and objectives.
struct FrontState {
  std::uint64_t generation = 0;  // generations evolved (0: the first population, evaluated)
  std::uint64_t evaluations = 0;
  std::vector<std::vector<double>> x;
  std::vector<std::vector<double>> f;
};

struct FrontOptions {
  // The family, budget, seed, threads, population, box, start and split as tune() takes them;
  // tune.objective gives the fault cost, the divergence bound and any required margins, and its
  // weights only the scalar cost each point records (training_cost, validation_cost).
  Options tune;
  std::vector<Metric> objectives;  // 2 .. 5, distinct, in the order of every objective vector
  // Continue from this state (of a search with the same options); empty: start afresh.
  std::optional<FrontState> resume;
  // Called on rank 0 with the state after every generation (the first population included);
  // returning false stops the search there.
  std::function<bool(const FrontState&)> generation_done;
};

struct FrontPoint {
  ControllerSpec controller;
  Tuning tuning;                   // how it was found, its objectives in `front`
  std::vector<double> training;    // its objectives on the training conditions
  std::vector<double> validation;  // on the validation conditions (empty without them)
};

struct Front {
  std::vector<FrontPoint> points;  // mutually non-dominated on training, by training itae order
  std::uint64_t evaluations = 0;
  std::uint64_t population = 0;
  std::uint64_t generations = 0;
  double wall_s = 0.0;
  bool stopped = false;  // generation_done asked to stop: no points
  bool served = false;   // a rank other than 0: no points
};

// The front of options.tune.family on `conditions` (the last options.tune.validation held back;
// conditions[k] runs on experiments.of(k)); nullopt with `error` set on invalid options or a
// state that does not belong to them.
[[nodiscard]] std::optional<Front> tune_front(const sim::ExperimentSet& experiments,
                                              const std::vector<sim::Condition>& conditions,
                                              const FrontOptions& options, std::string& error);

// The indices of the members of `f` that no other member dominates (minimisation: no worse in
// every objective and better in one); of members with equal objectives, only the first.
[[nodiscard]] std::vector<std::size_t> non_dominated(const std::vector<std::vector<double>>& f);

// The population NSGA-II runs with for `dimension` parameters when `requested` is 0: 5 x the
// dimension, at least 20, rounded up to a multiple of 4 (NSGA-II's pairing needs one).
[[nodiscard]] std::uint64_t front_population(std::uint64_t requested, std::size_t dimension);

}  // namespace fuzzypid::tune
