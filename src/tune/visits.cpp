// Which cells of a rule table a controller's runs visit: the share of the firing weight each
// cell gets, for the fuzzy-rules search's "unvisited cells keep the start" rule.
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <cmath>
#include <memory>

#include "evaluation.hpp"
#include "fuzzypid/controller/families.hpp"

namespace fuzzypid::tune {

namespace detail {

VisitMap visits_in(tbb::task_arena* arena, const ExperimentOf& ex,
                   const std::vector<sim::Condition>& conditions, const ControllerSpec& spec) {
  const supervisor::RuleTable<double> table = controller::rule_table(spec);
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

}  // namespace detail

VisitMap visits(const sim::ExperimentSet& experiments,
                const std::vector<sim::Condition>& conditions, const ControllerSpec& controller,
                unsigned threads) {
  std::unique_ptr<tbb::task_arena> arena;
  if (threads > 1) arena = std::make_unique<tbb::task_arena>(static_cast<int>(threads));
  return detail::visits_in(arena.get(), detail::experiments_of(experiments, conditions.size()),
                           conditions, controller);
}

}  // namespace fuzzypid::tune
