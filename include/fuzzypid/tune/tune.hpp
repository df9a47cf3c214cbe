// Robust tuning of a controller family on a training set of conditions (docs/tuning.md).
//
// Each family's parameters are searched in log10 inside a box (default_box); the objective of a
// parameter vector is, over the training conditions,
//
//   cost = sum ITAE (six joints)
//        + overshoot_weight x sum_joints max(0, overshoot_pct - overshoot_bound_pct)
//        + fault_cost per run that faults, diverges (|e| > divergence_rad) or gives a non-finite
//          ITAE (such a run adds only fault_cost),
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
#include "fuzzypid/sim/condition.hpp"
#include "fuzzypid/sim/experiment.hpp"

namespace fuzzypid::tune {

using controller::ControllerSpec;
using controller::Family;
using controller::Objective;
using controller::SearchBox;

// The searched parameters of a family, in order, with their default log10 boxes (units of the
// default controller file: acceleration gains, per tick at 0.05 s).
//   pid:       kp, ki, kd
//   scheduled: kp, ki, kd (K0, the gains on the path), ke, kec, rp, ri, rd (large-error ratios)
//   fuzzy:     kp, ki, kd (K0), ke, kec, sp, si, sd (output scales of the paper's tables)
[[nodiscard]] std::vector<SearchBox> default_box(Family family);

// The controller of `family` at the parameters 10^x (x in log10, in default_box order), with the
// units, PID options, bounds and rule base of `base`.
[[nodiscard]] ControllerSpec to_spec(Family family, const std::vector<double>& x,
                                     const ControllerSpec& base);
// The inverse: log10 of the family's parameters in `spec` (for starting points and tests).
[[nodiscard]] std::vector<double> from_spec(const ControllerSpec& spec);

struct Cost {
  double total = 0.0;
  double itae = 0.0;               // summed over the runs that did not fault
  double overshoot_penalty = 0.0;  // weighted
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

struct Options {
  Family family = Family::Fuzzy;
  std::uint64_t budget = 16000;  // objective evaluations, never exceeded
  std::uint64_t seed = 1;
  unsigned threads = 1;
  std::uint64_t population = 0;  // 0: 5 x the number of parameters, at least 20
  Objective objective{};
  std::vector<SearchBox> box;  // empty: default_box(family)
  ControllerSpec base{};       // units, PID options, bounds, rule base of the result
  // Called after every generation (and once at the end); may print.
  std::function<void(const Progress&)> progress;
};

struct Result {
  ControllerSpec controller;  // with its tuning record filled in (except conditions and set)
  Cost cost;
  std::uint64_t evaluations = 0;
  std::uint64_t population = 0;
  double wall_s = 0.0;
};

// Tunes on `training`; returns nullopt with `error` set for invalid options (budget below one
// population, a box that does not match the family, ...).
[[nodiscard]] std::optional<Result> tune(const sim::Experiment& experiment,
                                         const std::vector<sim::Condition>& training,
                                         const Options& options, std::string& error);
// The same with each training condition on its own robot and path (training[k] runs on
// experiments.of(k)).
[[nodiscard]] std::optional<Result> tune(const sim::ExperimentSet& experiments,
                                         const std::vector<sim::Condition>& training,
                                         const Options& options, std::string& error);

}  // namespace fuzzypid::tune
