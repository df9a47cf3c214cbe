// What the tuner's parts share inside the library (not installed): the experiment each condition
// runs on, the terms of one run's cost, and the evaluation of controllers over conditions
// (objective.cpp), of the rule-table cells their runs visit (visits.cpp) and of whole batches of
// candidates, over threads and ranks (runner.cpp), each summed in a fixed order so that the
// result depends neither on the thread count nor on the ranks.
#pragma once

#include <oneapi/tbb/task_arena.h>

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "fuzzypid/sim/certify.hpp"
#include "fuzzypid/tune/transport.hpp"
#include "fuzzypid/tune/tune.hpp"

namespace fuzzypid::tune::detail {

// The experiment of each condition (conditions[k] runs on *experiments[k]).
using ExperimentOf = std::vector<const sim::Experiment*>;

[[nodiscard]] ExperimentOf same_experiment(const sim::Experiment& ex, std::size_t n);
[[nodiscard]] ExperimentOf experiments_of(const sim::ExperimentSet& set, std::size_t n);

// The terms of one run's cost: the scalar objective's, weighted, and (with `metrics`) the raw
// sums over the joints that the fronts' objectives average. A run that faults has every term 0.
struct RunCost {
  double itae = 0.0, overshoot = 0.0, chatter = 0.0, effort = 0.0;  // weighted
  double effort_share = 0.0;   // sum over joints of rms(u) / u_limit
  double reversals_pct = 0.0;  // sum over joints of sim::reversals_pct(u)
  double overshoot_pct = 0.0;  // sum over joints of the overshoot, %
  bool faulted = false;
};

[[nodiscard]] RunCost run_cost(const sim::Experiment& ex, const sim::Condition& c,
                               const ControllerSpec& spec, const Objective& o, bool metrics);

// The scalar objective's cost of runs, summed in their order.
[[nodiscard]] Cost sum(const std::vector<RunCost>& runs, const Objective& o);

// The cost of `spec` over `conditions`, on `arena`'s threads when given (else in this thread).
[[nodiscard]] Cost evaluate_in(tbb::task_arena* arena, const ExperimentOf& ex,
                               const std::vector<sim::Condition>& conditions,
                               const ControllerSpec& spec, const Objective& o);

// The share of the rule-table firing weight each cell gets over the runs of `spec`.
[[nodiscard]] VisitMap visits_in(tbb::task_arena* arena, const ExperimentOf& ex,
                                 const std::vector<sim::Condition>& conditions,
                                 const ControllerSpec& spec);

// One set of conditions a runner evaluates candidates on.
struct ConditionSet {
  ExperimentOf experiments;
  std::vector<sim::Condition> conditions;
  std::optional<sim::PlantRanges> ranges;  // set when margins are screened or an objective
  double delay_s = 0.0;                    // the conditions' largest delay
};

// A candidate's frozen-gain margins over a set's plants (the tuner's screening options).
struct MarginCost {
  double disk_margin = 0.0;  // the worst over joints and plants; 0 when certify fails
  double shortfall = 0.0;    // margin_shortfall against the objective (1 when certify fails)
};

// The runs of batches of candidates (points of one ParameterSpace) over the training (set 0) or
// validation (set 1) conditions: on rank 0 of `transport` (or alone) the runs are spread over
// the ranks and over the arena's threads; on every other rank serve() answers rank 0 until it is
// done. Every rank must build its runner from the same inputs.
class Runner {
 public:
  Runner(tbb::task_arena* arena, const Transport* transport, const ParameterSpace& space,
         const Objective& objective, std::array<const ConditionSet*, 2> sets, bool metrics);
  Runner(const Runner&) = delete;
  Runner& operator=(const Runner&) = delete;
  // Rank 0: a runner that was not finished tells the others to give up.
  ~Runner();

  // Rank 0: per candidate, its runs on every condition of the set in order, then (with
  // `margins`) its margins: candidate k's runs are runs[k * conditions .. ], margins[k].
  struct Batch {
    std::vector<RunCost> runs;
    std::vector<MarginCost> margins;
  };
  [[nodiscard]] Batch run(const std::vector<std::vector<double>>& xs, int set, bool margins);

  // Rank 0: tells the other ranks that the search is over and which point it chose (empty for
  // none), once; the destructor sends an empty point if this was never called.
  void finish(const std::vector<double>& chosen);
  // Other ranks: answers rank 0 until it finishes; returns the point it chose (empty: none).
  [[nodiscard]] std::vector<double> serve();

  bool distributed() const noexcept { return transport_ != nullptr && transport_->size > 1; }
  bool worker() const noexcept { return transport_ != nullptr && transport_->rank != 0; }

 private:
  // The runs jobs[begin, end) of a batch, job j being candidate j / per-candidate, condition (or
  // margins) j % per-candidate, each encoded as a record of kRecord doubles.
  std::vector<double> compute(const std::vector<std::vector<double>>& xs, int set, bool margins,
                              std::size_t begin, std::size_t end) const;

  tbb::task_arena* arena_;
  const Transport* transport_;
  const ParameterSpace& space_;
  Objective objective_;
  std::array<const ConditionSet*, 2> sets_;
  bool metrics_;
  bool finished_ = false;
};

}  // namespace fuzzypid::tune::detail
