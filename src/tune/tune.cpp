#include "fuzzypid/tune/tune.hpp"

#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "evaluation.hpp"
#include "fuzzypid/controller/joint_controllers.hpp"
#include "fuzzypid/sim/certify.hpp"

namespace fuzzypid::tune {

namespace {

using detail::evaluate_in;
using detail::ExperimentOf;
using detail::experiments_of;
using detail::same_experiment;
using detail::visits_in;

// The runs of the controllers of one evaluation: training and validation conditions.
struct Split {
  ExperimentOf training_ex, validation_ex;
  std::vector<sim::Condition> training, validation;
};

Split split(const ExperimentOf& ex, const std::vector<sim::Condition>& conditions,
            std::size_t validation) {
  Split s;
  const std::size_t n = conditions.size() - validation;
  s.training_ex.assign(ex.begin(), ex.begin() + static_cast<std::ptrdiff_t>(n));
  s.validation_ex.assign(ex.begin() + static_cast<std::ptrdiff_t>(n), ex.end());
  s.training.assign(conditions.begin(), conditions.begin() + static_cast<std::ptrdiff_t>(n));
  s.validation.assign(conditions.begin() + static_cast<std::ptrdiff_t>(n), conditions.end());
  return s;
}

bool check_options(const Options& options, std::size_t conditions, std::string& error) {
  if (options.validation >= conditions) {
    error = "no training conditions (" + std::to_string(conditions) + " given, " +
            std::to_string(options.validation) + " held back for validation)";
    return false;
  }
  if (const std::string bad = controller::validate(options.base); !bad.empty()) {
    error = "base controller: " + bad;
    return false;
  }
  const Objective& o = options.objective;
  if (!std::isfinite(o.overshoot_bound_pct) || o.overshoot_bound_pct < 0 ||
      !std::isfinite(o.overshoot_weight) || o.overshoot_weight < 0 ||
      !std::isfinite(o.fault_cost) || o.fault_cost < 0 || !(o.divergence_rad > 0) ||
      !(o.chatter_weight >= 0.0 && std::isfinite(o.chatter_weight)) ||
      !(o.effort_weight >= 0.0 && std::isfinite(o.effort_weight)) ||
      !(o.chatter_limit_pct >= 0.0 && o.chatter_limit_pct <= 100.0)) {
    error =
        "objective weights must be finite and >= 0, the divergence bound > 0, the chatter limit "
        "within 0 .. 100 %";
    return false;
  }
  return true;
}

std::optional<Result> tune_on(const ExperimentOf& experiment,
                              const std::vector<sim::Condition>& conditions, const Options& options,
                              std::string& error) {
  if (!check_options(options, conditions.size(), error)) return std::nullopt;
  const Split data = split(experiment, conditions, options.validation);
  const unsigned threads = std::max(1u, options.threads);
  std::unique_ptr<tbb::task_arena> arena;
  if (threads > 1) arena = std::make_unique<tbb::task_arena>(static_cast<int>(threads));

  // The start, as a controller of the family; it also says which table cells are visited.
  // With --init the start must convert exactly; without one the base is only the template of
  // units, options and rule base (a fuzzy-rules table starts at ones).
  ControllerSpec start_spec;
  if (options.init) {
    if (!convert(*options.init, options.family, start_spec, error)) return std::nullopt;
  } else if (std::string ignored; !convert(options.base, options.family, start_spec, ignored)) {
    start_spec = options.base;
    start_spec.family = options.family;
    start_spec.tuning.reset();
    if (controller::family_traits(options.family).rule_table) {
      start_spec.supervisor.rule_table = controller::RuleTableSpec{};
      start_spec.supervisor.rule_file.clear();
      start_spec.supervisor.rule_model.reset();
    }
  }
  const ControllerSpec* start = &start_spec;
  VisitMap visit_map{};
  if (controller::family_traits(options.family).rule_table &&
      options.table.unvisited == Unvisited::Seed)
    visit_map = visits_in(arena.get(), data.training_ex, data.training, *start);
  auto space = ParameterSpace::create(options.family, *start, options.table, &visit_map, error,
                                      options.search_filter);
  if (!space) return std::nullopt;

  // The default box moves with the training tick when all training conditions share one.
  std::vector<SearchBox> box = space->box();
  if (start->units.form == controller::PidForm::PerTick && !data.training_ex.empty()) {
    const double tick = data.training_ex.front()->options().tick_s;
    bool one_tick = true;
    for (const sim::Experiment* e : data.training_ex)
      one_tick = one_tick && e->options().tick_s == tick;
    if (one_tick) box = box_for_tick(box, options.family, start->units.tick_s, tick);
  }
  for (const SearchBox& b : options.box) {
    const auto it =
        std::find_if(box.begin(), box.end(), [&](const SearchBox& d) { return d.name == b.name; });
    if (it == box.end()) {
      error = "the " + std::string(controller::to_string(options.family)) +
              " family has no parameter '" + b.name + "'";
      return std::nullopt;
    }
    *it = b;
  }
  const Objective& o = options.objective;
  // Margins required: the plants of the training conditions, computed once; every candidate's
  // frozen-gain margins over them are checked before it is simulated.
  std::optional<sim::PlantRanges> ranges;
  double delay_s = 0.0;
  if (o.requires_margins()) {
    ranges = sim::plant_ranges(data.training, data.training_ex, error);
    if (!ranges) return std::nullopt;
    delay_s = sim::largest_delay_s(data.training);
  }
  const double infeasible_cost = static_cast<double>(data.training.size() + 1) * o.fault_cost;
  const auto objective = [&](const std::vector<double>& x) {
    const ControllerSpec spec = space->to_spec(x);
    if (ranges) {
      std::string ignored;
      const auto cert = sim::certify(spec, *ranges, screening_options(delay_s), ignored);
      const double shortfall = cert ? margin_shortfall(*cert, o) : 1.0;
      // More than any feasible candidate (whose runs cost at most fault_cost each), and less the
      // closer it comes: the search is led back to the feasible region.
      if (shortfall > 0.0) return infeasible_cost * (1.0 + shortfall);
    }
    const Cost c = evaluate_in(arena.get(), data.training_ex, data.training, spec, o);
    return c.total + space->penalty(spec);
  };
  // Early stopping: every new best point of the search is scored on the validation conditions;
  // the result is the one that scores best there.
  std::vector<double> chosen;
  std::optional<Cost> chosen_validation;
  std::uint64_t validation_runs = 0;
  MinimizeOptions mo;
  mo.budget = options.budget;
  mo.seed = options.seed;
  mo.population = options.population;
  mo.progress = options.progress;
  if (options.init) mo.start = space->from_spec(*start);
  if (!data.validation.empty())
    mo.improved = [&](const std::vector<double>& x, double f) {
      if (ranges && f >= infeasible_cost) return;  // below the required margins
      const Cost v =
          evaluate_in(arena.get(), data.validation_ex, data.validation, space->to_spec(x), o);
      ++validation_runs;
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
  result.cost = evaluate_in(arena.get(), data.training_ex, data.training, result.controller, o);
  result.penalty = space->penalty(result.controller);
  result.validation = chosen_validation;
  controller::Tuning t;
  t.algorithm = "pagmo::sade (variant 2, jDE)";
  t.budget = options.budget;
  t.evaluations = m->evaluations;
  t.seed = options.seed;
  t.threads = threads;
  t.population = m->population;
  t.training_cost = result.cost.total + result.penalty;
  t.objective = o;
  t.box = box;
  t.on_bound = on_bound(chosen, box);
  t.validation_conditions = data.validation.size();
  if (chosen_validation) t.validation_cost = chosen_validation->total;
  if (controller::family_traits(options.family).rule_table) t.regulariser = space->record();
  result.controller.tuning = t;
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
  std::vector<controller::StageRecord> records;
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
    out.controller.tuning = results.back().controller.tuning;
    out.controller.tuning->training_cost = results[pick].controller.tuning->training_cost;
    out.controller.tuning->validation_cost = results[pick].controller.tuning->validation_cost;
    out.controller.tuning->on_bound = results[pick].controller.tuning->on_bound;
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
  controller::Tuning& t = *out.controller.tuning;
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
