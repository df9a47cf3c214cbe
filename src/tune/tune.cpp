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

#include "fuzzypid/sim/metrics.hpp"

namespace fuzzypid::tune {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

const char* const kNames[3][8] = {
    {"kp", "ki", "kd", nullptr, nullptr, nullptr, nullptr, nullptr},
    {"kp", "ki", "kd", "ke", "kec", "rp", "ri", "rd"},
    {"kp", "ki", "kd", "ke", "kec", "sp", "si", "sd"},
};

std::size_t dimension(Family f) {
  return f == Family::Pid ? 3 : 8;
}

// The cost of one run; `faulted` set when it adds only the fault cost.
double run_cost(const sim::Experiment& ex, const sim::Condition& c, const ControllerSpec& spec,
                const Objective& o, double& itae_out, double& penalty_out, bool& faulted) {
  sim::RunLimits limits;
  limits.max_error_rad = o.divergence_rad;
  const sim::RunResult r = ex.run(c, spec, limits);
  faulted = !r.ok || r.diverged || r.controller_faults != 0;
  itae_out = 0.0;
  penalty_out = 0.0;
  if (!faulted) {
    const auto m = sim::run_metrics(r.rows, ex.options().tick_s);
    for (const auto& j : m) {
      itae_out += j.itae;
      penalty_out += o.overshoot_weight * std::max(0.0, j.overshoot_pct - o.overshoot_bound_pct);
    }
    if (!std::isfinite(itae_out) || !std::isfinite(penalty_out)) faulted = true;
  }
  if (faulted) {
    itae_out = 0.0;
    penalty_out = 0.0;
    return o.fault_cost;
  }
  return itae_out + penalty_out;
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
  std::vector<double> cost(n), itae(n), penalty(n);
  std::vector<char> faulted(n);
  const auto one = [&](std::size_t k) {
    bool f = false;
    cost[k] = run_cost(*ex[k], conditions[k], spec, o, itae[k], penalty[k], f);
    faulted[k] = f ? 1 : 0;
  };
  if (arena != nullptr && n > 1) {
    arena->execute([&] { tbb::parallel_for(std::size_t{0}, n, one); });
  } else {
    for (std::size_t k = 0; k < n; ++k)
      one(k);
  }
  Cost c;
  for (std::size_t k = 0; k < n; ++k) {  // fixed order: the same sum with any thread count
    c.total += cost[k];
    c.itae += itae[k];
    c.overshoot_penalty += penalty[k];
    c.faulted_runs += faulted[k] != 0 ? 1 : 0;
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

std::vector<SearchBox> default_box(Family family) {
  // log10 bounds, acceleration units, per tick at 0.05 s (docs/tuning.md explains each).
  const double pid[3][2] = {{-1.0, 4.0}, {-6.0, 1.0}, {0.0, 4.0}};
  const double scales[2][2] = {{-1.0, 4.0}, {-3.0, 2.0}};               // ke, kec
  const double ratios[3][2] = {{-2.0, 2.0}, {-2.0, 2.0}, {-2.0, 2.0}};  // rp, ri, rd
  const double outputs[3][2] = {{0.0, 6.0}, {-4.0, 3.0}, {-2.0, 5.0}};  // sp, si, sd
  const std::size_t f = static_cast<std::size_t>(family);
  std::vector<SearchBox> box;
  for (std::size_t k = 0; k < 3; ++k)
    box.push_back({kNames[f][k], pid[k][0], pid[k][1]});
  if (family == Family::Pid) return box;
  for (std::size_t k = 0; k < 2; ++k)
    box.push_back({kNames[f][3 + k], scales[k][0], scales[k][1]});
  const auto& last = family == Family::Scheduled ? ratios : outputs;
  for (std::size_t k = 0; k < 3; ++k)
    box.push_back({kNames[f][5 + k], last[k][0], last[k][1]});
  return box;
}

ControllerSpec to_spec(Family family, const std::vector<double>& x, const ControllerSpec& base) {
  ControllerSpec s = base;
  s.family = family;
  s.tuning.reset();
  const auto p = [&x](std::size_t k) { return std::pow(10.0, x[k]); };
  s.gains = {p(0), p(1), p(2)};
  if (family != Family::Pid) {
    s.supervisor.error_scale = p(3);
    s.supervisor.error_rate_scale = p(4);
    s.supervisor.output_scale = {p(5), p(6), p(7)};
  }
  if (family == Family::Scheduled) s.supervisor.gain_update = control::GainUpdate::Absolute;
  if (family != Family::Fuzzy) {  // a rule file only means something to the fuzzy family
    s.supervisor.rule_file.clear();
    s.supervisor.rule_model.reset();
  }
  return s;
}

std::vector<double> from_spec(const ControllerSpec& s) {
  std::vector<double> x = {std::log10(s.gains.kp), std::log10(s.gains.ki), std::log10(s.gains.kd)};
  if (s.family != Family::Pid) {
    x.push_back(std::log10(s.supervisor.error_scale));
    x.push_back(std::log10(s.supervisor.error_rate_scale));
    for (double v : s.supervisor.output_scale)
      x.push_back(std::log10(v));
  }
  return x;
}

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
  report();
  // Self-adaptive DE (variant 2: rand/1/exp; jDE adaptation of F and CR), one generation per
  // call with memory so that the adaptation carries over; no early stop (ftol = xtol = 0).
  pagmo::sade algo(1u, 2u, 1u, 0.0, 0.0, true, static_cast<unsigned>(options.seed));
  for (std::uint64_t g = 0; g < generations; ++g) {
    pop = algo.evolve(pop);
    report();
  }
  Minimum m;
  m.x = pop.champion_x();
  m.f = pop.champion_f()[0];
  m.evaluations = state->count;
  m.population = pop_size;
  m.wall_s = elapsed();
  return m;
}

namespace {

std::optional<Result> tune_on(const ExperimentOf& experiment,
                              const std::vector<sim::Condition>& training, const Options& options,
                              std::string& error) {
  const std::size_t dim = dimension(options.family);
  const std::vector<SearchBox> box =
      options.box.empty() ? default_box(options.family) : options.box;
  const auto names = default_box(options.family);
  if (box.size() != dim) {
    error = "the search box has " + std::to_string(box.size()) + " parameters, the " +
            std::string(controller::to_string(options.family)) + " family " +
            std::to_string(dim);
    return std::nullopt;
  }
  for (std::size_t k = 0; k < dim; ++k) {
    if (box[k].name != names[k].name) {
      error = "search box entry " + std::to_string(k) + " is '" + box[k].name + "', expected '" +
              names[k].name + "'";
      return std::nullopt;
    }
  }
  if (training.empty()) {
    error = "no training conditions";
    return std::nullopt;
  }
  if (const std::string bad = controller::validate(options.base); !bad.empty()) {
    error = "base controller: " + bad;
    return std::nullopt;
  }
  const Objective& o = options.objective;
  if (!std::isfinite(o.overshoot_bound_pct) || o.overshoot_bound_pct < 0 ||
      !std::isfinite(o.overshoot_weight) || o.overshoot_weight < 0 ||
      !std::isfinite(o.fault_cost) || o.fault_cost < 0 || !(o.divergence_rad > 0)) {
    error = "objective weights must be finite and >= 0, the divergence bound > 0";
    return std::nullopt;
  }
  const unsigned threads = std::max(1u, options.threads);
  std::unique_ptr<tbb::task_arena> arena;
  if (threads > 1) arena = std::make_unique<tbb::task_arena>(static_cast<int>(threads));
  Cost best{kInf, 0.0, 0.0, 0};
  const auto objective = [&](const std::vector<double>& x) {
    const Cost c =
        evaluate_in(arena.get(), experiment, training, to_spec(options.family, x, options.base), o);
    if (c.total < best.total) best = c;
    return c.total;
  };
  MinimizeOptions mo;
  mo.budget = options.budget;
  mo.seed = options.seed;
  mo.population = options.population;
  mo.progress = options.progress;
  const auto m = minimize(objective, box, mo, error);
  if (!m) return std::nullopt;

  Result result;
  result.evaluations = m->evaluations;
  result.population = m->population;
  result.wall_s = m->wall_s;
  result.controller = to_spec(options.family, m->x, options.base);
  result.cost = best;
  controller::Tuning t;
  t.algorithm = "pagmo::sade (variant 2, jDE)";
  t.budget = options.budget;
  t.evaluations = m->evaluations;
  t.seed = options.seed;
  t.threads = threads;
  t.population = m->population;
  t.training_cost = m->f;
  t.objective = o;
  t.box = box;
  result.controller.tuning = t;
  return result;
}

}  // namespace

std::optional<Result> tune(const sim::Experiment& experiment,
                           const std::vector<sim::Condition>& training, const Options& options,
                           std::string& error) {
  return tune_on(same_experiment(experiment, training.size()), training, options, error);
}

std::optional<Result> tune(const sim::ExperimentSet& experiments,
                           const std::vector<sim::Condition>& training, const Options& options,
                           std::string& error) {
  return tune_on(experiments_of(experiments, training.size()), training, options, error);
}

}  // namespace fuzzypid::tune
