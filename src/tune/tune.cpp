#include "fuzzypid/tune/tune.hpp"

#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <pagmo/algorithms/sade.hpp>
#include <pagmo/population.hpp>
#include <pagmo/problem.hpp>
#include <pagmo/types.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "fuzzypid/controller/joint_controllers.hpp"
#include "fuzzypid/sim/certify.hpp"
#include "fuzzypid/sim/metrics.hpp"

namespace fuzzypid::tune {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The terms of one run's cost.
struct RunCost {
  double itae = 0.0, overshoot = 0.0, chatter = 0.0, effort = 0.0;
  bool faulted = false;
};

// The chatter and effort terms of a run's rows (tick-major, joints 1..6), unweighted.
void drive_terms(const std::vector<sim::TrajectoryRow>& rows, const robot::JointVector& limit,
                 double chatter_limit_pct, double& chatter, double& effort) {
  const std::size_t ticks = rows.size() / robot::kNumJoints;
  std::vector<double> u(ticks);
  chatter = 0.0;
  effort = 0.0;
  for (std::size_t j = 0; j < robot::kNumJoints; ++j) {
    double sum_sq = 0.0;
    for (std::size_t k = 0; k < ticks; ++k) {
      u[k] = rows[k * robot::kNumJoints + j].u;
      sum_sq += u[k] * u[k];
    }
    chatter += std::max(0.0, sim::reversals_pct(u) - chatter_limit_pct) / 100.0;
    if (ticks > 0 && limit[j] > 0.0 && std::isfinite(limit[j]))
      effort += std::sqrt(sum_sq / static_cast<double>(ticks)) / limit[j];
  }
}

// The cost of one run; `faulted` set when it adds only the fault cost.
RunCost run_cost(const sim::Experiment& ex, const sim::Condition& c, const ControllerSpec& spec,
                 const Objective& o) {
  sim::RunLimits limits;
  limits.max_error_rad = o.divergence_rad;
  const sim::RunResult r = ex.run(c, spec, limits);
  RunCost out;
  out.faulted = !r.ok || r.diverged || r.controller_faults != 0;
  if (!out.faulted) {
    const auto m = sim::run_metrics(r.rows, ex.options().tick_s);
    for (const auto& j : m) {
      out.itae += j.itae;
      out.overshoot += o.overshoot_weight * std::max(0.0, j.overshoot_pct - o.overshoot_bound_pct);
    }
    if (o.chatter_weight != 0.0 || o.effort_weight != 0.0) {
      double chatter = 0.0, effort = 0.0;
      drive_terms(r.rows, ex.output_limit(c, spec.units.gains), o.chatter_limit_pct, chatter,
                  effort);
      out.chatter = o.chatter_weight * chatter;
      out.effort = o.effort_weight * effort;
    }
    if (!std::isfinite(out.itae + out.overshoot + out.chatter + out.effort)) out.faulted = true;
  }
  if (out.faulted) return RunCost{0.0, 0.0, 0.0, 0.0, true};
  return out;
}

double total(const RunCost& r, const Objective& o) {
  return r.faulted ? o.fault_cost : r.itae + r.overshoot + r.chatter + r.effort;
}

// The experiment of each condition (conditions[k] runs on *experiments[k]).
using ExperimentOf = std::vector<const sim::Experiment*>;

ExperimentOf same_experiment(const sim::Experiment& ex, std::size_t n) {
  return ExperimentOf(n, &ex);
}

ExperimentOf experiments_of(const sim::ExperimentSet& set, std::size_t n) {
  ExperimentOf out(n);
  for (std::size_t k = 0; k < n; ++k)
    out[k] = &set.of(k);
  return out;
}

Cost evaluate_in(tbb::task_arena* arena, const ExperimentOf& ex,
                 const std::vector<sim::Condition>& conditions, const ControllerSpec& spec,
                 const Objective& o) {
  const std::size_t n = conditions.size();
  std::vector<RunCost> runs(n);
  const auto one = [&](std::size_t k) { runs[k] = run_cost(*ex[k], conditions[k], spec, o); };
  if (arena != nullptr && n > 1) {
    arena->execute([&] { tbb::parallel_for(std::size_t{0}, n, one); });
  } else {
    for (std::size_t k = 0; k < n; ++k)
      one(k);
  }
  Cost c;
  for (const RunCost& r : runs) {  // fixed order: the same sum with any thread count
    c.total += total(r, o);
    c.itae += r.itae;
    c.overshoot_penalty += r.overshoot;
    c.chatter_penalty += r.chatter;
    c.effort_penalty += r.effort;
    c.faulted_runs += r.faulted ? 1 : 0;
  }
  return c;
}

struct MinimizeState {
  std::function<double(const std::vector<double>&)> f;
  std::vector<SearchBox> box;
  std::uint64_t budget = 0;
  std::uint64_t count = 0;
  double best = kInf;
};

// pagmo's user-defined problem: counts every evaluation against the budget.
struct Problem {
  std::shared_ptr<MinimizeState> s;

  pagmo::vector_double fitness(const pagmo::vector_double& x) const {
    MinimizeState& st = *s;
    if (st.count >= st.budget) throw std::logic_error("evaluation budget exceeded");
    ++st.count;
    double v = st.f(x);
    if (!(v == v)) v = kInf;  // NaN: worst
    st.best = std::min(st.best, v);
    return {v};
  }

  std::pair<pagmo::vector_double, pagmo::vector_double> get_bounds() const {
    pagmo::vector_double lo, hi;
    for (const SearchBox& b : s->box) {
      lo.push_back(b.log10_min);
      hi.push_back(b.log10_max);
    }
    return {lo, hi};
  }

  std::string get_name() const { return "fuzzypid tuning objective"; }
};

}  // namespace

Cost evaluate(const sim::Experiment& experiment, const std::vector<sim::Condition>& conditions,
              const ControllerSpec& controller, const Objective& objective, unsigned threads) {
  std::unique_ptr<tbb::task_arena> arena;
  if (threads > 1) arena = std::make_unique<tbb::task_arena>(static_cast<int>(threads));
  return evaluate_in(arena.get(), same_experiment(experiment, conditions.size()), conditions,
                     controller, objective);
}

Cost evaluate(const sim::ExperimentSet& experiments, const std::vector<sim::Condition>& conditions,
              const ControllerSpec& controller, const Objective& objective, unsigned threads) {
  std::unique_ptr<tbb::task_arena> arena;
  if (threads > 1) arena = std::make_unique<tbb::task_arena>(static_cast<int>(threads));
  return evaluate_in(arena.get(), experiments_of(experiments, conditions.size()), conditions,
                     controller, objective);
}

std::optional<Minimum> minimize(const std::function<double(const std::vector<double>&)>& f,
                                const std::vector<SearchBox>& box, const MinimizeOptions& options,
                                std::string& error) {
  if (box.empty()) {
    error = "nothing to search";
    return std::nullopt;
  }
  for (const SearchBox& b : box) {
    if (!std::isfinite(b.log10_min) || !std::isfinite(b.log10_max) || b.log10_max < b.log10_min) {
      error = "search box '" + b.name + "' must have finite bounds, min <= max";
      return std::nullopt;
    }
  }
  const std::uint64_t pop_size =
      options.population != 0
          ? options.population
          : std::max<std::uint64_t>(20, 5 * static_cast<std::uint64_t>(box.size()));
  if (pop_size < 7) {
    error = "the population must be at least 7 (differential evolution)";
    return std::nullopt;
  }
  if (options.budget < 2 * pop_size) {
    error = "the budget (" + std::to_string(options.budget) +
            ") must cover at least two generations of the population (" +
            std::to_string(2 * pop_size) + " evaluations)";
    return std::nullopt;
  }
  auto state = std::make_shared<MinimizeState>();
  state->f = f;
  state->box = box;
  state->budget = options.budget;
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  const auto report = [&] {
    if (options.progress) options.progress({state->count, options.budget, state->best, elapsed()});
  };
  const std::uint64_t generations = (options.budget - pop_size) / pop_size;
  pagmo::problem prob{Problem{state}};
  pagmo::population pop{prob, static_cast<pagmo::population::size_type>(pop_size),
                        static_cast<unsigned>(options.seed)};
  if (!options.start.empty()) {
    if (options.start.size() != box.size()) {
      error = "the start point has " + std::to_string(options.start.size()) +
              " parameters, the box " + std::to_string(box.size());
      return std::nullopt;
    }
    // Replaces the worst random member (one more evaluation, counted like every other).
    std::vector<double> x = options.start;
    for (std::size_t k = 0; k < x.size(); ++k)
      x[k] = std::clamp(x[k], box[k].log10_min, box[k].log10_max);
    if (state->count >= state->budget) {
      error = "the budget does not cover the start point";
      return std::nullopt;
    }
    pop.set_x(pop.worst_idx(), x);
  }
  double last_best = kInf;
  const auto improved = [&] {
    if (options.improved && pop.champion_f()[0] < last_best) {
      last_best = pop.champion_f()[0];
      options.improved(pop.champion_x(), last_best);
    }
  };
  report();
  improved();
  // Self-adaptive DE (variant 2: rand/1/exp; jDE adaptation of F and CR), one generation per
  // call with memory so that the adaptation carries over; no early stop (ftol = xtol = 0).
  pagmo::sade algo(1u, 2u, 1u, 0.0, 0.0, true, static_cast<unsigned>(options.seed));
  for (std::uint64_t g = 0; g < generations && state->count + pop_size <= state->budget; ++g) {
    pop = algo.evolve(pop);
    report();
    improved();
  }
  Minimum m;
  m.x = pop.champion_x();
  m.f = pop.champion_f()[0];
  m.evaluations = state->count;
  m.population = pop_size;
  m.wall_s = elapsed();
  return m;
}

std::vector<controller::BoundHit> on_bound(const std::vector<double>& x,
                                           const std::vector<SearchBox>& box, double fraction) {
  std::vector<controller::BoundHit> hits;
  for (std::size_t k = 0; k < box.size() && k < x.size(); ++k) {
    const SearchBox& b = box[k];
    const double width = b.log10_max - b.log10_min;
    if (!(width > 0.0)) continue;
    const double margin = fraction * width;
    if (x[k] >= b.log10_max - margin) hits.push_back({b.name, true, x[k]});
    // The bottom of the derivative filter's box (a fiftieth of the tick, box_for_tick) is its
    // "off" end: a filter below it is inert, so ending there is no sign of a box too small.
    else if (x[k] <= b.log10_min + margin && b.name != kFilterParameter)
      hits.push_back({b.name, false, x[k]});
  }
  return hits;
}

namespace {

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

VisitMap visits_in(tbb::task_arena* arena, const ExperimentOf& ex,
                   const std::vector<sim::Condition>& conditions, const ControllerSpec& spec) {
  const control::RuleTable<double> table = controller::rule_table(spec);
  const std::size_t n = conditions.size();
  std::vector<VisitMap> per(n, VisitMap{});
  const auto one = [&](std::size_t k) {
    const sim::RunResult r = ex[k]->run(conditions[k], spec);
    for (const sim::TrajectoryRow& row : r.rows) {
      const double x = spec.supervisor.error_scale * row.error;
      const double y = spec.supervisor.error_rate_scale * row.error_rate;
      if (!std::isfinite(x) || !std::isfinite(y)) continue;
      const auto c = table.cell(x, y);
      for (std::size_t a = 0; a < 2; ++a)
        for (std::size_t b = 0; b < 2; ++b)
          if (c.i + a < RuleTableSpec::kSets && c.j + b < RuleTableSpec::kSets)
            per[k][c.i + a][c.j + b] += c.weight[a][b];
    }
  };
  if (arena != nullptr && n > 1)
    arena->execute([&] { tbb::parallel_for(std::size_t{0}, n, one); });
  else
    for (std::size_t k = 0; k < n; ++k)
      one(k);
  VisitMap sum{};
  double total = 0.0;
  for (const VisitMap& m : per)  // fixed order: the same sum with any thread count
    for (std::size_t i = 0; i < RuleTableSpec::kSets; ++i)
      for (std::size_t j = 0; j < RuleTableSpec::kSets; ++j) {
        sum[i][j] += m[i][j];
        total += m[i][j];
      }
  if (total > 0.0)
    for (auto& row : sum)
      for (double& v : row)
        v /= total;
  return sum;
}

}  // namespace

double margin_shortfall(const sim::Certificate& cert, const Objective& o) {
  const sim::MarginSummary m = sim::summarize(cert);
  double shortfall = 0.0;
  const auto below = [&](double required, double got) {
    if (required > 0.0 && !(got >= required))
      shortfall += (required - std::max(0.0, got)) / required;
  };
  below(o.min_disk_margin, m.disk_margin);
  below(o.min_gain_margin_db, m.gain_margin_db);
  below(o.min_phase_margin_deg, m.phase_margin_deg);
  below(o.min_delay_margin_ms, m.delay_margin_ms);
  return shortfall;
}

sim::CertifyOptions screening_options(double delay_s) {
  sim::CertifyOptions c;
  c.delay_s = delay_s;
  c.grid_points = 5;
  c.margin.grid_points = 400;
  c.margin.delay_ticks = false;
  c.lyapunov = false;
  return c;
}

namespace {

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

VisitMap visits(const sim::ExperimentSet& experiments,
                const std::vector<sim::Condition>& conditions, const ControllerSpec& controller,
                unsigned threads) {
  std::unique_ptr<tbb::task_arena> arena;
  if (threads > 1) arena = std::make_unique<tbb::task_arena>(static_cast<int>(threads));
  return visits_in(arena.get(), experiments_of(experiments, conditions.size()), conditions,
                   controller);
}

}  // namespace fuzzypid::tune
