// Multi-objective tuning (front.hpp): NSGA-II one generation at a time, each generation's
// offspring evaluated as one batch by the runner (over threads and ranks), the state after each
// generation handed out for checkpoints.
#include "fuzzypid/tune/front.hpp"

#include <pagmo/algorithms/nsga2.hpp>
#include <pagmo/bfe.hpp>
#include <pagmo/population.hpp>
#include <pagmo/problem.hpp>
#include <pagmo/types.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>

#include "evaluation.hpp"
#include "fuzzypid/controller/families.hpp"
#include "search.hpp"

namespace fuzzypid::tune {

namespace {

using detail::RunCost;
using Points = std::vector<std::vector<double>>;

// NSGA-II's operators (pagmo's defaults but the mutation probability, 1 / dimension: one
// parameter mutated per child on average).
constexpr double kCrossover = 0.95;
constexpr double kCrossoverIndex = 10.0;
constexpr double kMutationIndex = 50.0;

// splitmix64: the seeds of the generations and the first population's draws.
std::uint64_t mix(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// Evaluates a batch of points into objective vectors (the problem's batch fitness).
using BatchFitness = std::function<Points(const Points&)>;

// pagmo's user-defined problem: the box, the number of objectives and the batch fitness; every
// evaluation goes through the batch (nsga2 with pagmo's default bfe calls batch_fitness).
struct Problem {
  const BatchFitness* batch = nullptr;
  const std::vector<SearchBox>* box = nullptr;
  std::size_t objectives = 2;

  pagmo::vector_double fitness(const pagmo::vector_double& x) const { return (*batch)({x}).at(0); }
  pagmo::vector_double batch_fitness(const pagmo::vector_double& dvs) const {
    const std::size_t dim = box->size();
    Points xs(dvs.size() / dim);
    for (std::size_t k = 0; k < xs.size(); ++k)
      xs[k].assign(dvs.begin() + static_cast<std::ptrdiff_t>(k * dim),
                   dvs.begin() + static_cast<std::ptrdiff_t>((k + 1) * dim));
    pagmo::vector_double out;
    for (const auto& f : (*batch)(xs))
      out.insert(out.end(), f.begin(), f.end());
    return out;
  }
  pagmo::vector_double::size_type get_nobj() const { return objectives; }
  std::pair<pagmo::vector_double, pagmo::vector_double> get_bounds() const {
    pagmo::vector_double lo, hi;
    for (const SearchBox& b : *box) {
      lo.push_back(b.log10_min);
      hi.push_back(b.log10_max);
    }
    return {lo, hi};
  }
  std::string get_name() const { return "fuzzypid tuning front"; }
};

bool has(const std::vector<Metric>& m, Metric x) {
  return std::find(m.begin(), m.end(), x) != m.end();
}

bool dominates(const std::vector<double>& a, const std::vector<double>& b) {
  bool better = false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i] > b[i]) return false;
    if (a[i] < b[i]) better = true;
  }
  return better;
}

bool check(const FrontOptions& options, std::string& error) {
  const auto& m = options.objectives;
  if (m.size() < 2 || m.size() > kMetricNames.size()) {
    error = "a front needs 2 to " + std::to_string(kMetricNames.size()) + " objectives (" +
            fuzzypid::names_of(kMetricNames) + "), " + std::to_string(m.size()) + " given";
    return false;
  }
  for (std::size_t i = 0; i < m.size(); ++i)
    for (std::size_t j = i + 1; j < m.size(); ++j)
      if (m[i] == m[j]) {
        error =
            std::string("objective '") + fuzzypid::name_of(kMetricNames, m[i]) + "' given twice";
        return false;
      }
  return true;
}

// The objective vector of one candidate from its runs (and margins) on a set.
std::vector<double> objectives_of(const std::vector<Metric>& metrics, const RunCost* runs,
                                  std::size_t n, const detail::MarginCost* margin,
                                  const Objective& o, double penalty) {
  double itae = 0.0, effort = 0.0, chatter = 0.0, overshoot = 0.0;
  std::size_t faulted = 0;
  for (std::size_t k = 0; k < n; ++k) {  // fixed order
    itae += runs[k].itae;
    effort += runs[k].effort_share;
    chatter += runs[k].reversals_pct;
    overshoot += runs[k].overshoot_pct;
    faulted += runs[k].faulted ? 1 : 0;
  }
  const double fault = o.fault_cost * static_cast<double>(faulted);
  const double joint_runs = static_cast<double>(std::max<std::size_t>(1, n * robot::kNumJoints));
  std::vector<double> f;
  for (const Metric m : metrics) {
    double v = 0.0;
    switch (m) {
      case Metric::Itae:
        v = itae;
        break;
      case Metric::Effort:
        v = effort / joint_runs;
        break;
      case Metric::Chatter:
        v = chatter / joint_runs;
        break;
      case Metric::Overshoot:
        v = overshoot / joint_runs;
        break;
      case Metric::Margin:
        v = margin != nullptr ? -margin->disk_margin : 0.0;
        break;
    }
    f.push_back(v + fault + penalty);
  }
  // Below a required margin: worse than any feasible candidate in every objective, less so the
  // closer it comes (as the one-objective tuner scores it).
  if (margin != nullptr && margin->shortfall > 0.0 && o.requires_margins())
    for (double& v : f)
      v = static_cast<double>(n + 1) * o.fault_cost * (1.0 + margin->shortfall);
  return f;
}

}  // namespace

std::vector<std::size_t> non_dominated(const std::vector<std::vector<double>>& f) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < f.size(); ++i) {
    bool keep = true;
    for (std::size_t j = 0; j < f.size() && keep; ++j) {
      if (j == i) continue;
      if (dominates(f[j], f[i]) || (j < i && f[j] == f[i])) keep = false;
    }
    if (keep) out.push_back(i);
  }
  return out;
}

std::uint64_t front_population(std::uint64_t requested, std::size_t dimension) {
  if (requested != 0) return requested;
  const std::uint64_t p = std::max<std::uint64_t>(20, 5 * static_cast<std::uint64_t>(dimension));
  return (p + 3) / 4 * 4;
}

std::optional<Front> tune_front(const sim::ExperimentSet& experiments,
                                const std::vector<sim::Condition>& conditions,
                                const FrontOptions& options, std::string& error) {
  if (!check(options, error)) return std::nullopt;
  const Options& to = options.tune;
  const Objective& o = to.objective;
  const bool margin_objective = has(options.objectives, Metric::Margin);
  detail::Search search;
  if (!detail::prepare(detail::experiments_of(experiments, conditions.size()), conditions, to,
                       margin_objective || o.requires_margins(), margin_objective, search, error))
    return std::nullopt;
  const ParameterSpace& space = *search.space;
  const std::vector<SearchBox>& box = search.box;
  const std::size_t dim = box.size();
  const std::uint64_t pop = front_population(to.population, dim);
  if (pop < 8 || pop % 4 != 0) {
    error = "the population of a front must be a multiple of 4, at least 8 (NSGA-II); " +
            std::to_string(pop) + " given";
    return std::nullopt;
  }
  if (to.budget < 2 * pop) {
    error = "the budget (" + std::to_string(to.budget) +
            ") must cover at least two generations of the population (" + std::to_string(2 * pop) +
            " evaluations)";
    return std::nullopt;
  }
  const std::uint64_t generations = (to.budget - pop) / pop;
  detail::Runner runner(search.arena.get(), to.transport, space, o,
                        {&search.training, &search.validation}, true);
  if (runner.worker()) {
    (void)runner.serve();
    Front served;
    served.served = true;
    return served;
  }
  const auto start_time = std::chrono::steady_clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  };
  const bool screen = margin_objective || o.requires_margins();
  // Objective vectors of points on set 0 (training) or 1 (validation), with the scalar costs.
  const auto evaluate = [&](const Points& xs, int set, std::vector<Cost>* scalar) {
    const bool margins = set == 0 ? screen : margin_objective;
    const detail::Runner::Batch b = runner.run(xs, set, margins);
    const std::size_t n =
        set == 0 ? search.training.conditions.size() : search.validation.conditions.size();
    Points out;
    for (std::size_t k = 0; k < xs.size(); ++k) {
      const double penalty = space.penalty(space.to_spec(xs[k]));
      const RunCost* runs = b.runs.data() + k * n;
      out.push_back(objectives_of(options.objectives, runs, n, margins ? &b.margins.at(k) : nullptr,
                                  o, penalty));
      if (scalar != nullptr)
        scalar->push_back(detail::sum(std::vector<RunCost>(runs, runs + n), o));
    }
    return out;
  };
  const BatchFitness training_fitness = [&](const Points& xs) { return evaluate(xs, 0, nullptr); };

  FrontState state;
  if (options.resume) {
    state = *options.resume;
    bool fits = state.x.size() == pop && state.f.size() == pop && state.generation <= generations &&
                state.evaluations == pop * (1 + state.generation);
    for (std::size_t k = 0; fits && k < pop; ++k)
      fits = state.x[k].size() == dim && state.f[k].size() == options.objectives.size();
    if (!fits) {
      error = "the state to resume is not one of this search (population " + std::to_string(pop) +
              " of " + std::to_string(dim) + " parameters, " +
              std::to_string(options.objectives.size()) + " objectives, " +
              std::to_string(generations) + " generations)";
      return std::nullopt;
    }
  } else {
    // The first population: uniform in the box from 53-bit draws of splitmix64 (the same on
    // every platform), the start (clipped into the box) as its first member when given.
    std::uint64_t s = mix(to.seed);
    state.x.assign(pop, std::vector<double>(dim));
    for (auto& x : state.x)
      for (std::size_t i = 0; i < dim; ++i) {
        s = mix(s);
        const double u = static_cast<double>(s >> 11) * 0x1.0p-53;
        x[i] = box[i].log10_min + u * (box[i].log10_max - box[i].log10_min);
      }
    if (to.init) {
      std::vector<double> x = space.from_spec(search.start);
      for (std::size_t i = 0; i < dim && i < x.size(); ++i)
        state.x[0][i] = std::clamp(x[i], box[i].log10_min, box[i].log10_max);
    }
    state.f = training_fitness(state.x);
    state.evaluations = pop;
  }
  const auto report = [&] {
    if (!to.progress) return;
    double best = state.f.front().front();
    for (const auto& f : state.f)
      best = std::min(best, f.front());
    to.progress({state.evaluations, to.budget, best, elapsed()});
  };
  report();
  if (options.generation_done && !options.resume && !options.generation_done(state)) {
    Front stopped;
    stopped.stopped = true;
    return stopped;
  }
  while (state.generation < generations) {
    // Generation g's offspring depend on the state and (seed, g) alone: a fresh population and
    // algorithm are built from them every generation, so that a resumed search is the same.
    pagmo::problem prob{Problem{&training_fitness, &box, options.objectives.size()}};
    const auto seed = static_cast<unsigned>(mix(to.seed ^ mix(state.generation + 1)) >> 32);
    pagmo::population p{prob, 0u, seed};
    for (std::size_t k = 0; k < pop; ++k)
      p.push_back(state.x[k], state.f[k]);
    pagmo::nsga2 algo(1u, kCrossover, kCrossoverIndex, 1.0 / static_cast<double>(dim),
                      kMutationIndex, seed);
    algo.set_bfe(pagmo::bfe{});
    try {
      p = algo.evolve(p);
    } catch (const std::exception& e) {
      error = std::string("NSGA-II: ") + e.what();
      return std::nullopt;
    }
    state.x = p.get_x();
    state.f = p.get_f();
    ++state.generation;
    state.evaluations += pop;
    report();
    if (options.generation_done && !options.generation_done(state)) {
      Front stopped;
      stopped.stopped = true;
      return stopped;
    }
  }

  // The front: the final population's non-dominated members, by their first objective.
  std::vector<std::size_t> idx = non_dominated(state.f);
  std::stable_sort(idx.begin(), idx.end(),
                   [&](std::size_t a, std::size_t b) { return state.f[a] < state.f[b]; });
  Points xs;
  for (const std::size_t k : idx)
    xs.push_back(state.x[k]);
  std::vector<Cost> training_cost, validation_cost;
  const Points training = evaluate(xs, 0, &training_cost);
  Points validation;
  if (!search.validation.conditions.empty()) validation = evaluate(xs, 1, &validation_cost);
  runner.finish(xs.empty() ? std::vector<double>{} : xs.front());

  Front front;
  front.evaluations = state.evaluations;
  front.population = pop;
  front.generations = state.generation;
  front.wall_s = elapsed();
  for (std::size_t k = 0; k < xs.size(); ++k) {
    FrontPoint point;
    point.controller = space.to_spec(xs[k]);
    point.training = training[k];
    if (!validation.empty()) point.validation = validation[k];
    const double penalty = space.penalty(point.controller);
    Tuning t;
    t.algorithm = "pagmo::nsga2 (cr 0.95, eta_c 10, m 1/dimension, eta_m 50)";
    t.budget = to.budget;
    t.evaluations = state.evaluations;
    t.seed = to.seed;
    t.threads = 0;  // not recorded: the front is the same for any threads and ranks
    t.population = pop;
    t.training_cost = training_cost[k].total + penalty;
    t.objective = o;
    t.box = box;
    t.on_bound = on_bound(xs[k], box);
    t.validation_conditions = search.validation.conditions.size();
    if (!validation.empty()) t.validation_cost = validation_cost[k].total;
    if (controller::family_traits(to.family).rule_table) t.regulariser = space.record();
    for (std::size_t m = 0; m < options.objectives.size(); ++m)
      t.front.push_back(
          {fuzzypid::name_of(kMetricNames, options.objectives[m]), point.training[m],
           validation.empty() ? std::numeric_limits<double>::quiet_NaN() : point.validation[m]});
    point.tuning = t;
    front.points.push_back(std::move(point));
  }
  return front;
}

}  // namespace fuzzypid::tune
