// What every search of the tuner sets up before its first evaluation (not installed): the
// training and validation conditions, the threads, the start converted into the family, its
// parameter space and the box, shared by tune.cpp (one objective) and front.cpp (a front).
#pragma once

#include <oneapi/tbb/task_arena.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "evaluation.hpp"

namespace fuzzypid::tune::detail {

// The conditions of one evaluation: the training ones and the validation ones held back.
struct Split {
  ExperimentOf training_ex, validation_ex;
  std::vector<sim::Condition> training, validation;
};

struct Search {
  Split data;
  unsigned threads = 1;
  std::unique_ptr<tbb::task_arena> arena;  // null for one thread
  ControllerSpec start;                    // the start as a controller of the family
  std::optional<ParameterSpace> space;
  std::vector<SearchBox> box;  // the space's box, moved with the tick, with options.box applied
  // The runners' condition sets (their plant ranges as prepare() was asked).
  ConditionSet training, validation;
};

// Checks the options and sets up `search` (which must not move afterwards: runners hold it);
// false with `error` set on invalid options. With `margins` the training set's plant ranges are
// computed, with `validation_margins` the validation set's too.
[[nodiscard]] bool prepare(const ExperimentOf& experiment,
                           const std::vector<sim::Condition>& conditions, const Options& options,
                           bool margins, bool validation_margins, Search& search,
                           std::string& error);

}  // namespace fuzzypid::tune::detail
