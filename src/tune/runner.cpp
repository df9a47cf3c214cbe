// The runs of batches of candidates, spread over the threads of one process and over the ranks
// of a Transport (evaluation.hpp). Message from rank 0 to the others: {op, set, margins, n, dim,
// x[0] .. x[n-1]}, op 1 a batch and op 2 the end (with the chosen point as x[0], n = 0 or 1).
// Answer: the records of the rank's block of jobs. Every rank computes the same block bounds
// from n, so nothing else travels.
#include <oneapi/tbb/parallel_for.h>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "evaluation.hpp"

namespace fuzzypid::tune::detail {

namespace {

constexpr std::size_t kRecord = 8;  // doubles per job
constexpr double kBatch = 1.0;
constexpr double kEnd = 2.0;

// The first job of `rank`'s block of `jobs` over `size` ranks.
std::size_t block_begin(std::size_t jobs, int rank, int size) {
  return jobs * static_cast<std::size_t>(rank) / static_cast<std::size_t>(size);
}

std::vector<double> encode(double op, int set, bool margins,
                           const std::vector<std::vector<double>>& xs) {
  const std::size_t dim = xs.empty() ? 0 : xs.front().size();
  std::vector<double> m{op, static_cast<double>(set), margins ? 1.0 : 0.0,
                        static_cast<double>(xs.size()), static_cast<double>(dim)};
  m.reserve(m.size() + xs.size() * dim);
  for (const auto& x : xs)
    m.insert(m.end(), x.begin(), x.end());
  return m;
}

std::vector<std::vector<double>> decode_points(const std::vector<double>& m) {
  const auto n = static_cast<std::size_t>(m.at(3));
  const auto dim = static_cast<std::size_t>(m.at(4));
  std::vector<std::vector<double>> xs(n, std::vector<double>(dim));
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t i = 0; i < dim; ++i)
      xs[k][i] = m.at(5 + k * dim + i);
  return xs;
}

}  // namespace

Runner::Runner(tbb::task_arena* arena, const Transport* transport, const ParameterSpace& space,
               const Objective& objective, std::array<const ConditionSet*, 2> sets, bool metrics)
    : arena_(arena),
      transport_(transport),
      space_(space),
      objective_(objective),
      sets_(sets),
      metrics_(metrics) {}

Runner::~Runner() {
  if (distributed() && !worker() && !finished_) finish({});
}

std::vector<double> Runner::compute(const std::vector<std::vector<double>>& xs, int set,
                                    bool margins, std::size_t begin, std::size_t end) const {
  const ConditionSet& cs = *sets_.at(static_cast<std::size_t>(set));
  const std::size_t per = cs.conditions.size() + (margins ? 1 : 0);
  std::vector<double> out((end - begin) * kRecord, 0.0);
  if (begin >= end) return out;
  // The controllers of the candidates this block touches.
  const std::size_t first = begin / per;
  const std::size_t last = (end - 1) / per;
  std::vector<ControllerSpec> specs(last - first + 1);
  for (std::size_t k = first; k <= last; ++k)
    specs[k - first] = space_.to_spec(xs[k]);
  const auto one = [&](std::size_t j) {
    const ControllerSpec& spec = specs[j / per - first];
    const std::size_t c = j % per;
    double* r = &out[(j - begin) * kRecord];
    if (c < cs.conditions.size()) {
      const RunCost rc = run_cost(*cs.experiments[c], cs.conditions[c], spec, objective_, metrics_);
      r[0] = rc.itae;
      r[1] = rc.overshoot;
      r[2] = rc.chatter;
      r[3] = rc.effort;
      r[4] = rc.effort_share;
      r[5] = rc.reversals_pct;
      r[6] = rc.overshoot_pct;
      r[7] = rc.faulted ? 1.0 : 0.0;
      return;
    }
    std::string ignored;
    const auto cert = cs.ranges
                          ? sim::certify(spec, *cs.ranges, screening_options(cs.delay_s), ignored)
                          : std::nullopt;
    r[0] = cert ? sim::summarize(*cert).disk_margin : 0.0;
    r[1] = cert ? margin_shortfall(*cert, objective_) : 1.0;
  };
  if (arena_ != nullptr && end - begin > 1) {
    arena_->execute([&] { tbb::parallel_for(begin, end, one); });
  } else {
    for (std::size_t j = begin; j < end; ++j)
      one(j);
  }
  return out;
}

Runner::Batch Runner::run(const std::vector<std::vector<double>>& xs, int set, bool margins) {
  const ConditionSet& cs = *sets_.at(static_cast<std::size_t>(set));
  const std::size_t per = cs.conditions.size() + (margins ? 1 : 0);
  const std::size_t jobs = xs.size() * per;
  std::vector<double> records;
  if (distributed()) {
    const std::vector<double> message = encode(kBatch, set, margins, xs);
    for (int r = 1; r < transport_->size; ++r)
      transport_->send(r, message);
    records = compute(xs, set, margins, 0, block_begin(jobs, 1, transport_->size));
    for (int r = 1; r < transport_->size; ++r) {
      const std::vector<double> part = transport_->receive(r);
      records.insert(records.end(), part.begin(), part.end());
    }
  } else {
    records = compute(xs, set, margins, 0, jobs);
  }
  // A rank answering another number of records breaks the protocol: an exception (tune_front
  // reports it as its error), never a batch read short.
  if (records.size() != jobs * kRecord)
    throw std::runtime_error("the ranks answered " + std::to_string(records.size()) +
                             " values for " + std::to_string(jobs) + " runs of " +
                             std::to_string(kRecord));
  Batch b;
  b.runs.reserve(xs.size() * cs.conditions.size());
  for (std::size_t j = 0; j < jobs; ++j) {
    const double* r = &records[j * kRecord];
    if (j % per < cs.conditions.size()) {
      b.runs.push_back(RunCost{r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7] != 0.0});
    } else {
      b.margins.push_back(MarginCost{r[0], r[1]});
    }
  }
  return b;
}

void Runner::finish(const std::vector<double>& chosen) {
  if (finished_) return;
  finished_ = true;
  if (!distributed() || worker()) return;
  std::vector<std::vector<double>> xs;
  if (!chosen.empty()) xs.push_back(chosen);
  const std::vector<double> message = encode(kEnd, 0, false, xs);
  for (int r = 1; r < transport_->size; ++r)
    transport_->send(r, message);
}

std::vector<double> Runner::serve() {
  for (;;) {
    const std::vector<double> m = transport_->receive(0);
    if (m.size() < 5 || m[0] != kBatch) {
      finished_ = true;
      const auto xs = m.size() >= 5 ? decode_points(m) : std::vector<std::vector<double>>{};
      return xs.empty() ? std::vector<double>{} : xs.front();
    }
    const int set = static_cast<int>(m[1]);
    const bool margins = m[2] != 0.0;
    const auto xs = decode_points(m);
    const ConditionSet& cs = *sets_.at(static_cast<std::size_t>(set));
    const std::size_t jobs = xs.size() * (cs.conditions.size() + (margins ? 1 : 0));
    transport_->send(
        0, compute(xs, set, margins, block_begin(jobs, transport_->rank, transport_->size),
                   block_begin(jobs, transport_->rank + 1, transport_->size)));
  }
}

}  // namespace fuzzypid::tune::detail
