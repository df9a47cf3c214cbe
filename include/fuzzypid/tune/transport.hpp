// How the runs of one generation are spread over processes (MPI ranks, docs/tuning.md "Fronts and
// ranks"): rank 0 runs the search and hands out runs; every other rank builds the same problem
// from the same inputs and serves them until rank 0 says it is done. The library knows messages
// of doubles only, so it depends on no message-passing library; `fuzzypid tune` gives it one
// over MPI.
//
// Results do not depend on the ranks: a run's cost is a function of its controller and condition
// alone, and rank 0 sums the costs in the same fixed order whoever computed them.
#pragma once

#include <functional>
#include <vector>

namespace fuzzypid::tune {

struct Transport {
  int rank = 0;  // this process, 0 .. size-1
  int size = 1;  // processes sharing the work
  // Blocking point-to-point messages between ranks; a failure ends the process (as MPI's default
  // error handler does), so neither returns an error.
  std::function<void(int to, const std::vector<double>& message)> send;
  std::function<std::vector<double>(int from)> receive;
};

}  // namespace fuzzypid::tune
