// What the tuner's parts share inside the library (not installed): the experiment each condition
// runs on, and the parallel evaluation of one controller over conditions (objective.cpp) and of
// the rule-table cells its runs visit (visits.cpp), each summed in a fixed order so that the
// result does not depend on the thread count.
#pragma once

#include <oneapi/tbb/task_arena.h>

#include <cstddef>
#include <vector>

#include "fuzzypid/tune/tune.hpp"

namespace fuzzypid::tune::detail {

// The experiment of each condition (conditions[k] runs on *experiments[k]).
using ExperimentOf = std::vector<const sim::Experiment*>;

[[nodiscard]] ExperimentOf same_experiment(const sim::Experiment& ex, std::size_t n);
[[nodiscard]] ExperimentOf experiments_of(const sim::ExperimentSet& set, std::size_t n);

// The cost of `spec` over `conditions`, on `arena`'s threads when given (else in this thread).
[[nodiscard]] Cost evaluate_in(tbb::task_arena* arena, const ExperimentOf& ex,
                               const std::vector<sim::Condition>& conditions,
                               const ControllerSpec& spec, const Objective& o);

// The share of the rule-table firing weight each cell gets over the runs of `spec`.
[[nodiscard]] VisitMap visits_in(tbb::task_arena* arena, const ExperimentOf& ex,
                                 const std::vector<sim::Condition>& conditions,
                                 const ControllerSpec& spec);

}  // namespace fuzzypid::tune::detail
