// Robust tuning of a controller family on a training set of conditions (docs/tuning.md).
//
// Each family's parameters are searched in log10 inside a box (default_box); the objective of a
// parameter vector is, over the training conditions,
//
//   cost = sum ITAE (six joints)
//        + overshoot_weight x sum_joints max(0, overshoot_pct - overshoot_bound_pct)
//        + chatter_weight x sum_joints max(0, reversals_pct(u) - chatter_limit_pct) / 100
//        + effort_weight x sum_joints rms(u) / u_limit
//        + fault_cost per run that faults, diverges (|e| > divergence_rad) or gives a non-finite
//          ITAE (such a run adds only fault_cost),
//
// and, when the objective requires margins (min_disk_margin, ...), a candidate whose frozen-gain
// margins over the training plants fall short is not simulated: it costs
// (runs + 1) fault_cost (1 + shortfall), more than any feasible candidate (margin_shortfall),
//
// with u a joint's command over the run and u_limit its output limit (the torque limit over J^
// in acceleration units). reversals_pct (sim/metrics.hpp, as metrics.csv reports it) is the
// share of ticks on which the command's change reverses direction, counting only changes larger
// than 1 % of the command's range in the run: ringing at the Nyquist rate scores 100 %, a smooth
// command nearly 0; with chatter_limit_pct > 0 only the share above it costs, so that a large
// weight acts as a bound on every joint of every run. ITAE alone rewards that ringing, which costs nothing on a rigid, delay-free
// plant and excites the first resonance of a real joint.
//
// minimised by pagmo2's self-adaptive differential evolution (pagmo::sade, jDE adaptation) under a
// hard budget of objective evaluations. The conditions of one evaluation run in parallel on
// `threads` threads (oneTBB) and are summed in a fixed order, so the result depends on the seed
// only -- not on the thread count. Nothing but the given training set is ever evaluated.
//
// Library fuzzypid::tune (offline, allocates, never in a control loop).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "fuzzypid/controller/controller_spec.hpp"
#include "fuzzypid/sim/certify.hpp"
#include "fuzzypid/sim/condition.hpp"
#include "fuzzypid/sim/experiment.hpp"
#include "fuzzypid/tune/parameters.hpp"
#include "fuzzypid/tune/record.hpp"
#include "fuzzypid/tune/transport.hpp"

namespace fuzzypid::tune {

struct Cost {
  double total = 0.0;
  double itae = 0.0;               // summed over the runs that did not fault
  double overshoot_penalty = 0.0;  // weighted
  double chatter_penalty = 0.0;    // weighted
  double effort_penalty = 0.0;     // weighted
  std::size_t faulted_runs = 0;
};

// The objective of one controller on a set of conditions (threads: 1 = serial).
[[nodiscard]] Cost evaluate(const sim::Experiment& experiment,
                            const std::vector<sim::Condition>& conditions,
                            const ControllerSpec& controller, const Objective& objective,
                            unsigned threads = 1);
// The same with each condition on its own robot and path: conditions[k] runs on
// experiments.of(k) (experiments built from these conditions).
[[nodiscard]] Cost evaluate(const sim::ExperimentSet& experiments,
                            const std::vector<sim::Condition>& conditions,
                            const ControllerSpec& controller, const Objective& objective,
                            unsigned threads = 1);

// How far `cert`'s worst margins (sim::summarize) fall below the objective's minima: the sum of
// (required − got) / required over the margins required and not met (0: feasible).
[[nodiscard]] double margin_shortfall(const sim::Certificate& cert, const Objective& o);
// The certify options the tuner screens candidates with: frozen-gain margins only (no Lyapunov
// certificate, no whole-tick delay scan), 5 points per axis of a supervisor's grid, 400
// frequencies; `delay_s` the training conditions' largest delay.
[[nodiscard]] sim::CertifyOptions screening_options(double delay_s);

struct Progress {
  std::uint64_t evaluations = 0;
  std::uint64_t budget = 0;
  double best_cost = 0.0;
  double elapsed_s = 0.0;
};

// The optimiser alone: minimises f over the box (x in the box's units, here log10) with
// pagmo::sade under a hard budget of evaluations of f. Deterministic for a given seed.
struct MinimizeOptions {
  std::uint64_t budget = 16000;
  std::uint64_t seed = 1;
  std::uint64_t population = 0;  // 0: 5 x the dimension, at least 20
  // A member of the first generation (clipped into the box); empty: all drawn at random.
  std::vector<double> start;
  // Called when the best point changes (after its generation), e.g. for validation.
  std::function<void(const std::vector<double>& x, double f)> improved;
  std::function<void(const Progress&)> progress;
};

struct Minimum {
  std::vector<double> x;
  double f = 0.0;
  std::uint64_t evaluations = 0;
  std::uint64_t population = 0;
  double wall_s = 0.0;
};

[[nodiscard]] std::optional<Minimum> minimize(
    const std::function<double(const std::vector<double>&)>& f, const std::vector<SearchBox>& box,
    const MinimizeOptions& options, std::string& error);

// The parameters of x (in the box's units) that lie within `fraction` of their box's width of a
// side, in box order. A box of zero width (a parameter held fixed) is never reported, nor the
// derivative filter "tf" at its bottom (a filter shorter than that is inert: the "off" end).
[[nodiscard]] std::vector<BoundHit> on_bound(const std::vector<double>& x,
                                             const std::vector<SearchBox>& box,
                                             double fraction = 0.01);

struct Options {
  Family family{};               // the list's first (controller/families.hpp): the fixed PID
  std::uint64_t budget = 16000;  // objective evaluations, never exceeded
  std::uint64_t seed = 1;
  unsigned threads = 1;
  std::uint64_t population = 0;  // 0: 5 x the number of parameters, at least 20
  Objective objective{};
  // Overrides of the family's default box, by name (a name the family does not search is an
  // error).
  std::vector<SearchBox> box;
  ControllerSpec base{};  // units, PID options, bounds, rule base of the result
  // The controller the search starts from (one member of the first generation), converted
  // exactly into the family (tune::convert); for fuzzy-rules also the values of the held cells
  // and the controller whose training runs say which cells are visited. Without it the base.
  std::optional<ControllerSpec> init;
  TableOptions table{};  // fuzzy-rules only
  // Search the derivative filter's time constant Tf beside the family's parameters (the last
  // parameter, "tf": ParameterSpace::create); without it the result keeps the base's Tf. On by
  // default: an unfiltered derivative of an encoder's angle chatters (docs/tuning.md, "Chatter").
  bool search_filter = true;
  // Search a bandwidth scale for each of joints 2 .. 6 relative to joint 1 (ControllerSpec::
  // bandwidth_scale; parameters "bandwidth_j2" .. "bandwidth_j6", last): one loop shape, each
  // joint placed at its own speed. Off by default: without it the result keeps the start's scales.
  bool search_bandwidth = false;
  // The last `validation` of the given conditions are held back: never trained on, they choose
  // among the best points of the search (early stopping) and among stages.
  std::size_t validation = 0;
  // Called after every generation (and once at the end); may print.
  std::function<void(const Progress&)> progress;
  // The ranks sharing the runs (transport.hpp); null: this process alone. Every rank calls the
  // same function with the same options and conditions; only rank 0's result holds a controller.
  const Transport* transport = nullptr;
};

struct Result {
  ControllerSpec controller;
  Tuning tuning;                     // how it was found (all but conditions and set)
  Cost cost;                         // on the training conditions, without the regulariser
  double penalty = 0.0;              // the regulariser's cost of the result
  std::optional<Cost> validation;    // on the held-back conditions
  std::vector<double> stage_wall_s;  // tune_staged: the wall time of each stage
  std::uint64_t evaluations = 0;
  std::uint64_t population = 0;
  double wall_s = 0.0;
  bool served = false;  // a rank other than 0: it ran rank 0's runs and holds no result
};

// Tunes on `conditions` (the last options.validation of them held back); returns nullopt with
// `error` set for invalid options (budget below one population, a box that does not match the
// family, ...).
[[nodiscard]] std::optional<Result> tune(const sim::Experiment& experiment,
                                         const std::vector<sim::Condition>& conditions,
                                         const Options& options, std::string& error);
// The same with each condition on its own robot and path (conditions[k] runs on
// experiments.of(k)).
[[nodiscard]] std::optional<Result> tune(const sim::ExperimentSet& experiments,
                                         const std::vector<sim::Condition>& conditions,
                                         const Options& options, std::string& error);

// Staged tuning: one stage per entry, each started from the last one's result converted
// exactly into its family (the first from options.init or the base); the budgets add up to the
// run's total. With a validation split the result is the stage whose result, converted into the
// last stage's family, has the lowest validation cost (the last stage without one).
struct Stage {
  Family family{};
  std::uint64_t budget = 0;
};

[[nodiscard]] std::optional<Result> tune_staged(const sim::ExperimentSet& experiments,
                                                const std::vector<sim::Condition>& conditions,
                                                const std::vector<Stage>& stages,
                                                const Options& options, std::string& error);

// The share of the firing weight each node of a fuzzy-rules controller's table receives over the
// runs of `controller` on the conditions (all joints, all ticks).
[[nodiscard]] VisitMap visits(const sim::ExperimentSet& experiments,
                              const std::vector<sim::Condition>& conditions,
                              const ControllerSpec& controller, unsigned threads = 1);

}  // namespace fuzzypid::tune
