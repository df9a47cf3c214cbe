// The tuner's optimiser: self-adaptive differential evolution (pagmo2's sade) over a box in
// log10, every evaluation counted against the budget; and which parameters ended on their box.
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

#include "fuzzypid/tune/tune.hpp"

namespace fuzzypid::tune {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

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

std::vector<BoundHit> on_bound(const std::vector<double>& x, const std::vector<SearchBox>& box,
                               double fraction) {
  std::vector<BoundHit> hits;
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

}  // namespace fuzzypid::tune
