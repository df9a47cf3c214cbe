#include "fuzzypid/tune/tune.hpp"

#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <functional>
#include <limits>
#include <utility>

#include "evaluation.hpp"
#include "fuzzypid/controller/joint_controllers.hpp"
#include "fuzzypid/sim/certify.hpp"
#include "search.hpp"

namespace fuzzypid::tune {

namespace {

using detail::ExperimentOf;
using detail::experiments_of;
using detail::same_experiment;

std::optional<Result> tune_on(const ExperimentOf& experiment,
                              const std::vector<sim::Condition>& conditions, const Options& options,
                              std::string& error) {
  detail::Search search;
  if (!detail::prepare(experiment, conditions, options, options.objective.requires_margins(), false,
                       search, error))
    return std::nullopt;
  const detail::Split& data = search.data;
  const ControllerSpec* start = &search.start;
  const auto& space = search.space;
  const std::vector<SearchBox>& box = search.box;
  tbb::task_arena* const arena = search.arena.get();
  const Objective& o = options.objective;
  // Margins required: every candidate's frozen-gain margins over the training plants are checked
  // before it is simulated.
  const detail::ConditionSet& training_set = search.training;
  const std::optional<sim::PlantRanges>& ranges = training_set.ranges;
  detail::Runner runner(arena, options.transport, *space, o, {&search.training, &search.validation},
                        false);
  if (runner.worker()) {
    const std::vector<double> chosen = runner.serve();
    if (chosen.empty()) {
      error = "rank 0 stopped the search";
      return std::nullopt;
    }
    Result served;
    served.served = true;
    served.controller = space->to_spec(chosen);
    return served;
  }
  const double infeasible_cost = static_cast<double>(data.training.size() + 1) * o.fault_cost;
  const auto cost_of = [&](const std::vector<double>& x, int set) {
    return detail::sum(runner.run({x}, set, false).runs, o);
  };
  // The screening of one candidate at a time is most of a margin-screened search's work: its six
  // joints run on the arena's threads (the candidate's runs do too, below).
  sim::CertifyOptions screening = screening_options(training_set.delay_s);
  if (arena != nullptr)
    screening.for_each_joint = [arena](std::size_t n,
                                       const std::function<void(std::size_t)>& joint) {
      arena->execute([&] { tbb::parallel_for(std::size_t{0}, n, joint); });
    };
  const auto objective = [&](const std::vector<double>& x) {
    const ControllerSpec spec = space->to_spec(x);
    if (ranges) {
      std::string ignored;
      const auto cert = sim::certify(spec, *ranges, screening, ignored);
      const double shortfall = cert ? margin_shortfall(*cert, o) : 1.0;
      // More than any feasible candidate (whose runs cost at most fault_cost each), and less the
      // closer it comes: the search is led back to the feasible region.
      if (shortfall > 0.0) return infeasible_cost * (1.0 + shortfall);
    }
    return cost_of(x, 0).total + space->penalty(spec);
  };
  // Early stopping: every new best point of the search is scored on the validation conditions;
  // the result is the one that scores best there.
  std::vector<double> chosen;
  std::optional<Cost> chosen_validation;
  MinimizeOptions mo;
  mo.budget = options.budget;
  mo.seed = options.seed;
  mo.population = options.population;
  mo.progress = options.progress;
  if (options.init) mo.start = space->from_spec(*start);
  if (!data.validation.empty())
    mo.improved = [&](const std::vector<double>& x, double f) {
      if (ranges && f >= infeasible_cost) return;  // below the required margins
      const Cost v = cost_of(x, 1);
      if (!chosen_validation || v.total <= chosen_validation->total) {
        chosen_validation = v;
        chosen = x;
      }
    };
  const auto m = minimize(objective, box, mo, error);
  if (!m) return std::nullopt;
  if (chosen.empty()) chosen = m->x;

  Result result;
  result.evaluations = m->evaluations;
  result.population = m->population;
  result.wall_s = m->wall_s;
  result.controller = space->to_spec(chosen);
  result.cost = cost_of(chosen, 0);
  runner.finish(chosen);
  result.penalty = space->penalty(result.controller);
  result.validation = chosen_validation;
  Tuning t;
  t.algorithm = "pagmo::sade (variant 2, jDE)";
  t.budget = options.budget;
  t.evaluations = m->evaluations;
  t.seed = options.seed;
  t.threads = 0;  // not recorded: the result is the same for any threads and ranks
  t.population = m->population;
  t.training_cost = result.cost.total + result.penalty;
  t.objective = o;
  t.box = box;
  t.on_bound = on_bound(chosen, box);
  t.validation_conditions = data.validation.size();
  if (chosen_validation) t.validation_cost = chosen_validation->total;
  if (controller::family_traits(options.family).rule_table) t.regulariser = space->record();
  result.tuning = t;
  return result;
}

std::optional<Result> staged_on(const ExperimentOf& experiment,
                                const std::vector<sim::Condition>& conditions,
                                const std::vector<Stage>& stages, const Options& options,
                                std::string& error) {
  if (stages.empty()) {
    error = "no stages";
    return std::nullopt;
  }
  const Family last = stages.back().family;
  std::uint64_t total = 0;
  std::vector<Result> results;
  std::vector<StageRecord> records;
  std::optional<ControllerSpec> init = options.init;
  for (const Stage& stage : stages) {
    Options o = options;
    o.family = stage.family;
    o.budget = stage.budget;
    o.init = init;
    if (stage.family != last) o.box.clear();  // --box names the last stage's parameters
    auto r = tune_on(experiment, conditions, o, error);
    if (!r) {
      error = std::string("stage ") + controller::to_string(stage.family) + ": " + error;
      return std::nullopt;
    }
    total += stage.budget;
    records.push_back(
        {stage.family, stage.budget, r->evaluations, r->cost.total + r->penalty,
         r->validation ? r->validation->total : std::numeric_limits<double>::quiet_NaN()});
    init = r->controller;
    results.push_back(std::move(*r));
  }
  if (results.back().served) {  // another rank's stages: nothing of its own to choose
    Result served;
    served.served = true;
    return served;
  }
  // Every stage's result as a controller of the last family (exact), chosen by validation.
  std::size_t pick = results.size() - 1;
  for (std::size_t k = 0; k + 1 < results.size(); ++k) {
    if (!results[k].validation || !results[pick].validation) continue;
    ControllerSpec converted;
    if (!convert(results[k].controller, last, converted, error)) continue;
    if (results[k].validation->total < results[pick].validation->total) pick = k;
  }
  Result out = results[pick];
  if (pick + 1 != results.size()) {
    (void)convert(results[pick].controller, last, out.controller, error);
    out.tuning = results.back().tuning;
    out.tuning.training_cost = results[pick].tuning.training_cost;
    out.tuning.validation_cost = results[pick].tuning.validation_cost;
    out.tuning.on_bound = results[pick].tuning.on_bound;
    out.penalty = 0.0;  // a converted table of ones is as smooth and monotone as its schedule
  }
  std::uint64_t evaluations = 0;
  double wall = 0.0;
  for (const Result& r : results) {
    evaluations += r.evaluations;
    wall += r.wall_s;
  }
  out.evaluations = evaluations;
  out.wall_s = wall;
  out.stage_wall_s.clear();
  for (const Result& r : results)
    out.stage_wall_s.push_back(r.wall_s);
  Tuning& t = out.tuning;
  t.budget = total;
  t.evaluations = evaluations;
  t.stages = records;
  return out;
}

}  // namespace

std::optional<Result> tune(const sim::Experiment& experiment,
                           const std::vector<sim::Condition>& conditions, const Options& options,
                           std::string& error) {
  return tune_on(same_experiment(experiment, conditions.size()), conditions, options, error);
}

std::optional<Result> tune(const sim::ExperimentSet& experiments,
                           const std::vector<sim::Condition>& conditions, const Options& options,
                           std::string& error) {
  return tune_on(experiments_of(experiments, conditions.size()), conditions, options, error);
}

std::optional<Result> tune_staged(const sim::ExperimentSet& experiments,
                                  const std::vector<sim::Condition>& conditions,
                                  const std::vector<Stage>& stages, const Options& options,
                                  std::string& error) {
  return staged_on(experiments_of(experiments, conditions.size()), conditions, stages, options,
                   error);
}

}  // namespace fuzzypid::tune
