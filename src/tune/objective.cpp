// The tuner's objective: the cost of one controller over conditions (ITAE, overshoot above its
// bound, chatter and effort, a fixed cost per faulted run) and a certificate's shortfall against
// the margins the objective requires.
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "evaluation.hpp"
#include "fuzzypid/sim/certify.hpp"
#include "fuzzypid/sim/metrics.hpp"

namespace fuzzypid::tune {

namespace {

using detail::RunCost;

// The chatter and effort terms of a run's rows (tick-major, joints 1..6), unweighted; with
// `metrics` also the unlimited reversal share and the effort share summed over the joints.
void drive_terms(const std::vector<sim::TrajectoryRow>& rows, const robot::JointVector& limit,
                 double chatter_limit_pct, double& chatter, double& effort, RunCost* metrics) {
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
    const double reversals = sim::reversals_pct(u);
    chatter += std::max(0.0, reversals - chatter_limit_pct) / 100.0;
    double share = 0.0;
    if (ticks > 0 && limit[j] > 0.0 && std::isfinite(limit[j]))
      share = std::sqrt(sum_sq / static_cast<double>(ticks)) / limit[j];
    effort += share;
    if (metrics != nullptr) {
      metrics->reversals_pct += reversals;
      metrics->effort_share += share;
    }
  }
}

double total(const RunCost& r, const Objective& o) {
  return r.faulted ? o.fault_cost : r.itae + r.overshoot + r.chatter + r.effort;
}

}  // namespace

namespace detail {

RunCost run_cost(const sim::Experiment& ex, const sim::Condition& c, const ControllerSpec& spec,
                 const Objective& o, bool metrics) {
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
      if (metrics) out.overshoot_pct += j.overshoot_pct;
    }
    if (o.chatter_weight != 0.0 || o.effort_weight != 0.0 || metrics) {
      double chatter = 0.0, effort = 0.0;
      drive_terms(r.rows, ex.output_limit(c, spec.units.gains), o.chatter_limit_pct, chatter,
                  effort, metrics ? &out : nullptr);
      out.chatter = o.chatter_weight * chatter;
      out.effort = o.effort_weight * effort;
    }
    if (!std::isfinite(out.itae + out.overshoot + out.chatter + out.effort)) out.faulted = true;
    if (metrics && !std::isfinite(out.effort_share + out.reversals_pct + out.overshoot_pct))
      out.faulted = true;
  }
  if (out.faulted) return RunCost{0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, true};
  return out;
}

ExperimentOf same_experiment(const sim::Experiment& ex, std::size_t n) {
  return ExperimentOf(n, &ex);
}

ExperimentOf experiments_of(const sim::ExperimentSet& set, std::size_t n) {
  ExperimentOf out(n);
  for (std::size_t k = 0; k < n; ++k)
    out[k] = &set.of(k);
  return out;
}

Cost sum(const std::vector<RunCost>& runs, const Objective& o) {
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

Cost evaluate_in(tbb::task_arena* arena, const ExperimentOf& ex,
                 const std::vector<sim::Condition>& conditions, const ControllerSpec& spec,
                 const Objective& o) {
  const std::size_t n = conditions.size();
  std::vector<RunCost> runs(n);
  const auto one = [&](std::size_t k) {
    runs[k] = run_cost(*ex[k], conditions[k], spec, o, false);
  };
  if (arena != nullptr && n > 1) {
    arena->execute([&] { tbb::parallel_for(std::size_t{0}, n, one); });
  } else {
    for (std::size_t k = 0; k < n; ++k)
      one(k);
  }
  return sum(runs, o);
}

}  // namespace detail

Cost evaluate(const sim::Experiment& experiment, const std::vector<sim::Condition>& conditions,
              const ControllerSpec& controller, const Objective& objective, unsigned threads) {
  std::unique_ptr<tbb::task_arena> arena;
  if (threads > 1) arena = std::make_unique<tbb::task_arena>(static_cast<int>(threads));
  return detail::evaluate_in(arena.get(), detail::same_experiment(experiment, conditions.size()),
                             conditions, controller, objective);
}

Cost evaluate(const sim::ExperimentSet& experiments, const std::vector<sim::Condition>& conditions,
              const ControllerSpec& controller, const Objective& objective, unsigned threads) {
  std::unique_ptr<tbb::task_arena> arena;
  if (threads > 1) arena = std::make_unique<tbb::task_arena>(static_cast<int>(threads));
  return detail::evaluate_in(arena.get(), detail::experiments_of(experiments, conditions.size()),
                             conditions, controller, objective);
}

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

}  // namespace fuzzypid::tune
