// `fuzzypid tune`: robust tuning of a controller family on a condition set (docs/tuning.md), and
// `fuzzypid export-header`: a controller file as a self-contained C++ header.
#include <signal.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cinttypes>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "commands.hpp"
#include "front_checkpoint.hpp"
#if FUZZYPID_HAVE_MPI
#include "mpi_transport.hpp"
#endif
#include "fuzzypid/codegen/export_header.hpp"
#include "fuzzypid/controller/families.hpp"
#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid/robot/path.hpp"
#include "fuzzypid/robot/robot_model.hpp"
#include "fuzzypid/sim/certify.hpp"
#include "fuzzypid/sim/condition_set.hpp"
#include "fuzzypid/sim/experiment.hpp"
#include "fuzzypid/tune/front.hpp"
#include "fuzzypid/tune/tune.hpp"
#include "fuzzypid_support/bounded_read.hpp"
#include "output_files.hpp"
#include "robot_options.hpp"

namespace fuzzypid::cli {

namespace {

namespace cf = controller_file;

constexpr double kMaxLog10 = 300.0;

bool parse_box(const std::string& text, tune::SearchBox& box) {
  const auto eq = text.find('=');
  const auto colon = text.find(':', eq == std::string::npos ? 0 : eq);
  if (eq == std::string::npos || colon == std::string::npos) return false;
  box.name = text.substr(0, eq);
  char* end = nullptr;
  const std::string lo = text.substr(eq + 1, colon - eq - 1);
  const std::string hi = text.substr(colon + 1);
  box.log10_min = std::strtod(lo.c_str(), &end);
  if (lo.empty() || *end != '\0') return false;
  box.log10_max = std::strtod(hi.c_str(), &end);
  if (hi.empty() || *end != '\0') return false;
  // 10^x must be a finite, non-zero double: |x| <= 300 (DBL_MAX is 1.8e308, DBL_MIN 2.2e-308).
  return std::isfinite(box.log10_min) && std::isfinite(box.log10_max) &&
         box.log10_min <= box.log10_max && std::fabs(box.log10_min) <= kMaxLog10 &&
         std::fabs(box.log10_max) <= kMaxLog10;
}

struct TuneOptions {
  std::string family_name, conditions, set = "training", out, base_file, init_file, stages;
  std::uint64_t budget = 16000, seed = 1, population = 0, validation = 0;
  bool budget_given = false;
  std::string symmetry = "even", unvisited = "seed", partition = "tuned";
  tune::TableOptions table;
  unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  tune::Objective objective;
  std::vector<std::string> boxes;
  bool quiet = false;
  bool search_filter = true;
  bool search_bandwidth = false;
  bool allow_faults = false;
  GivenOptions given;
  // A front (--objectives): its folder, and the checkpoint written after every generation and the
  // one resumed from.
  std::string objectives, front_out, checkpoint, resume, report_set;
  // The ranks sharing the runs (null: this process alone); asked once the options are parsed.
  std::function<const tune::Transport*()> transport;
};

// "itae,effort" -> the metrics, in order; empty when any name is unknown or repeated.
std::vector<tune::Metric> parse_objectives(const std::string& text) {
  std::vector<tune::Metric> out;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    const auto m = fuzzypid::parse_enum(tune::kMetricNames, text.substr(begin, end - begin));
    if (!m || std::find(out.begin(), out.end(), *m) != out.end()) return {};
    out.push_back(*m);
    begin = end + 1;
  }
  return out;
}

// The largest total budget: --budget's own upper bound, which the stages' sum may not pass either.
constexpr std::uint64_t kMaxBudget = 100000000;

// "pid:8000,scheduled:24000,fuzzy-rules:32000" -> stages; false on any malformed entry.
bool parse_stages(const std::string& text, std::vector<tune::Stage>& stages, std::string& error) {
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    const std::string entry = text.substr(begin, end - begin);
    const std::size_t colon = entry.find(':');
    const auto family = colon == std::string::npos ? std::nullopt
                                                   : fuzzypid::parse_enum(controller::kFamilyNames,
                                                                          entry.substr(0, colon));
    char* stop = nullptr;
    const std::string number = colon == std::string::npos ? "" : entry.substr(colon + 1);
    const unsigned long long budget = std::strtoull(number.c_str(), &stop, 10);
    if (!family || number.empty() || *stop != '\0' || number[0] == '-' || budget < 14 ||
        budget > 100000000ull) {
      error = "'" + entry + "': expected FAMILY:BUDGET with FAMILY one of " +
              fuzzypid::names_of(controller::kFamilyNames) + " and 14 <= BUDGET <= 100000000";
      return false;
    }
    stages.push_back({*family, budget});
    begin = end + 1;
  }
  return !stages.empty();
}

// How a result stands once its record is complete: its margins over the training conditions and
// whether it misses a margin the options require (judged as the search judged it).
struct Completion {
  sim::MarginSummary margins;
  bool short_of_required = false;  // as the search screened: a failed search
  // The recorded margins (certify's full grid, validation plants included) below the requirement
  // the screened search met: warned of, since the file's [margins] then shows less than asked.
  bool record_short_of_required = false;
};

// Completes the tuning record of `spec`, to be written to `out`: every file name in it relative to
// out's folder, as a reader resolves it (the rule file, named relative to the folder of the file it
// came from, the base or else the start; the conditions, robots, paths and start), the files'
// hashes, the tick, the set and the description; and its [margins] and certificate over the
// training conditions (validation ones included). training.conditions[k] runs on
// experiments.of(k). Progress notes go to stderr unless --quiet.
std::optional<Completion> complete_record(const TuneOptions& t, const std::string& out,
                                          controller::Family family, const tune::Options& opt,
                                          const sim::ConditionSet& training,
                                          const sim::ExperimentSet& experiments,
                                          cf::ControllerFile& file, std::string& error) {
  controller::ControllerSpec& spec = file.controller;
  if (!spec.supervisor.rule_file.empty()) {
    const std::filesystem::path from =
        std::filesystem::path(t.base_file.empty() ? t.init_file : t.base_file).parent_path();
    spec.supervisor.rule_file =
        path_from_folder_of(out, (from / spec.supervisor.rule_file).string());
  }
  tune::Tuning& record = *file.tuning;
  record.conditions = path_from_folder_of(out, t.conditions);
  // The condition file as read: a file edited later (or while the tune ran) shows in its hash.
  if (!t.conditions.empty() &&
      std::none_of(record.trained_on.begin(), record.trained_on.end(),
                   [](const tune::TrainedOn& f) { return f.kind == "conditions"; }))
    record.trained_on.push_back({"conditions", record.conditions, cf::file_hash(t.conditions)});
  for (std::size_t k = 0; k < training.conditions.size(); ++k) {
    const sim::RobotSetup& setup = experiments.of(k).setup();
    const auto add = [&](const char* kind, const std::string& file) {
      const std::string written = path_from_folder_of(out, file);
      for (const auto& f : record.trained_on)
        if (f.kind == kind && f.file == written) return;
      record.trained_on.push_back({kind, written, cf::file_hash(file)});
    };
    if (!setup.urdf.empty()) add("urdf", setup.urdf);
    if (!setup.path.empty()) add("path", setup.path);
  }
  {
    double tick = experiments.of(0).options().tick_s;
    for (std::size_t k = 1; k < training.conditions.size(); ++k)
      if (experiments.of(k).options().tick_s != tick) tick = 0.0;
    record.tick_s = tick;
  }
  record.set = t.set;
  if (!t.init_file.empty()) record.init = path_from_folder_of(out, t.init_file);
  spec.description = "tuned " + std::string(controller::to_string(family)) + " on " + t.conditions +
                     " [" + t.set + "]";
  sim::CertifyOptions co;
  co.delay_s = sim::largest_delay_s(training.conditions);
  const auto cert = sim::certify(spec, training.conditions, experiments, co, error);
  if (!cert) return std::nullopt;
  file.margins = sim::margin_record(*cert);
  file.margins->conditions = record.conditions;
  file.margins->set = t.set;
  Completion done;
  done.margins = sim::summarize(*cert);
  if (!t.quiet)
    std::fprintf(stderr,
                 "fuzzypid tune: margins over the training plants: disk %.3f, gain %.2f dB, "
                 "phase %.1f deg, delay %.1f ms; %s\n",
                 done.margins.disk_margin, done.margins.gain_margin_db,
                 done.margins.phase_margin_deg, done.margins.delay_margin_ms,
                 cert->verdict.c_str());
  // The requirement is judged as the search judged it: on the training conditions (the
  // validation ones held back) with the screening options.
  if (opt.objective.requires_margins()) {
    const std::vector<sim::Condition> trained(
        training.conditions.begin(),
        training.conditions.end() - static_cast<std::ptrdiff_t>(t.validation));
    const auto screened = sim::certify(
        spec, trained, experiments, tune::screening_options(sim::largest_delay_s(trained)), error);
    if (!screened) return std::nullopt;
    done.short_of_required = tune::margin_shortfall(*screened, opt.objective) > 0.0;
    done.record_short_of_required = tune::margin_shortfall(*cert, opt.objective) > 0.0;
  }
  return done;
}

// Set by SIGINT or SIGTERM while a checkpointed front search runs: the search stops once the
// generation under way is done and its state saved.
volatile std::sig_atomic_t g_stop_signal = 0;
extern "C" void request_stop(int sig) {
  g_stop_signal = sig;
}

// Installs request_stop for SIGINT and SIGTERM while it lives (on every rank, so that a signal
// mpirun forwards stops no worker before rank 0 is done). The outputs' clean-up then leaves these
// signals alone: the run ends normally and discards what it has not committed.
class StopOnSignal {
 public:
  StopOnSignal() {
    struct sigaction sa {};
    sa.sa_handler = request_stop;
    sigemptyset(&sa.sa_mask);
    for (std::size_t k = 0; k < kSignals.size(); ++k)
      installed_[k] = sigaction(kSignals[k], &sa, &previous_[k]) == 0;
  }
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;
  ~StopOnSignal() {
    for (std::size_t k = 0; k < kSignals.size(); ++k)
      if (installed_[k]) sigaction(kSignals[k], &previous_[k], nullptr);
  }

 private:
  static constexpr std::array<int, 2> kSignals{SIGINT, SIGTERM};
  std::array<struct sigaction, 2> previous_{};
  std::array<bool, 2> installed_{};
};

// A value on one line of a checkpoint.
std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  return text;
}

std::string exact(double d) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%a", d);
  return buf;
}

// What a front search's result depends on: every option that shapes it and the contents of its
// inputs (not the threads, the ranks or the outputs, which change nothing of it).
Fingerprint fingerprint_of(const TuneOptions& t, const tune::FrontOptions& fo,
                           const sim::ConditionSet& training) {
  const tune::Objective& o = fo.tune.objective;
  std::string objectives, boxes;
  for (const tune::Metric m : fo.objectives)
    objectives +=
        (objectives.empty() ? "" : ",") + std::string(fuzzypid::name_of(tune::kMetricNames, m));
  for (const std::string& b : t.boxes)
    boxes += (boxes.empty() ? "" : " ") + b;
  const auto hash = [](const std::string& file) {
    return file.empty() ? std::string("-") : cf::file_hash(file);
  };
  Fingerprint f = {
      {"family", t.family_name},
      {"objectives", objectives},
      {"budget", std::to_string(t.budget)},
      {"seed", std::to_string(t.seed)},
      {"population", std::to_string(t.population)},
      {"validation", std::to_string(t.validation)},
      {"set", one_line(t.set)},
      {"report-set", one_line(t.report_set.empty() ? "-" : t.report_set)},
      {"conditions-fnv1a64", hash(t.conditions)},
      {"base-fnv1a64", hash(t.base_file)},
      {"init-fnv1a64", hash(t.init_file)},
      {"search-filter", t.search_filter ? "yes" : "no"},
      {"per-joint-bandwidth", t.search_bandwidth ? "yes" : "no"},
      {"symmetry", t.symmetry},
      {"unvisited", t.unvisited},
      {"partition", t.partition},
      {"smoothness", exact(t.table.smoothness)},
      {"monotone", exact(t.table.monotone)},
      {"visit-threshold", exact(t.table.visit_threshold)},
      {"cell-log10", exact(t.table.cell_log10)},
      {"overshoot-bound", exact(o.overshoot_bound_pct)},
      {"overshoot-weight", exact(o.overshoot_weight)},
      {"fault-cost", exact(o.fault_cost)},
      {"chatter-weight", exact(o.chatter_weight)},
      {"chatter-limit", exact(o.chatter_limit_pct)},
      {"effort-weight", exact(o.effort_weight)},
      {"min-disk-margin", exact(o.min_disk_margin)},
      {"min-gain-margin", exact(o.min_gain_margin_db)},
      {"min-phase-margin", exact(o.min_phase_margin_deg)},
      {"min-delay-margin", exact(o.min_delay_margin_ms)},
      {"divergence", exact(o.divergence_rad)},
      {"box", one_line(boxes.empty() ? "-" : boxes)},
  };
  std::vector<std::string> seen;
  for (const sim::Condition& c : training.conditions)
    for (const std::string& file : {c.robot.urdf, c.robot.path})
      if (!file.empty() && std::find(seen.begin(), seen.end(), file) == seen.end()) {
        seen.push_back(file);
        f.emplace_back("input-fnv1a64", one_line(file) + " " + hash(file));
      }
  return f;
}

// The largest checkpoint read back: a state of 10^6 members would be far below it.
constexpr std::size_t kMaxCheckpointBytes = std::size_t{1} << 30;

// `fuzzypid tune --objectives ... --front-out DIR`: the front of `family` written as DIR/front.csv
// and one controller file per point; `out_set` is null on ranks other than 0.
// `searched` is the training set, followed by --report-set's conditions when given (the front's
// validation conditions then).
int run_front(const TuneOptions& t, controller::Family family, const tune::Options& opt,
              const sim::ConditionSet& training, const sim::ConditionSet& searched,
              const sim::ExperimentSet& experiments, OutputSet* out_set) {
  tune::FrontOptions fo;
  fo.tune = opt;
  fo.objectives = parse_objectives(t.objectives);
  const Fingerprint fingerprint = fingerprint_of(t, fo, searched);
  std::string error;
  if (!t.resume.empty() && out_set != nullptr) {
    std::string text, reason;
    if (!support::read_file_bounded(t.resume, kMaxCheckpointBytes, text, reason)) {
      std::fprintf(stderr, "fuzzypid tune: --resume: %s\n", reason.c_str());
      return kExitFailure;
    }
    fo.resume = parse_checkpoint(text, t.resume, fingerprint, error);
    if (!fo.resume) {
      std::fprintf(stderr, "fuzzypid tune: --resume: %s\n", error.c_str());
      return kExitFailure;
    }
    if (!t.quiet)
      std::fprintf(stderr,
                   "fuzzypid tune: resuming after generation %" PRIu64 " (%" PRIu64
                   " evaluations) from %s\n",
                   fo.resume->generation, fo.resume->evaluations, t.resume.c_str());
  }
  std::optional<StopOnSignal> stop_on_signal;
  g_stop_signal = 0;
  if (!t.checkpoint.empty()) stop_on_signal.emplace();
  std::string checkpoint_error;
  if (!t.checkpoint.empty() && out_set != nullptr)
    fo.generation_done = [&](const tune::FrontState& state) {
      checkpoint_error =
          write_output_file(t.checkpoint, checkpoint_text(fingerprint, state), "tune");
      return checkpoint_error.empty() && g_stop_signal == 0;
    };
  auto front = tune::tune_front(experiments, searched.conditions, fo, error);
  if (!front) {
    std::fprintf(stderr, "fuzzypid tune: %s\n", error.c_str());
    return kExitUsage;
  }
  if (front->served) return kExitOk;
  if (front->stopped) {
    if (!checkpoint_error.empty()) {
      std::fprintf(stderr, "fuzzypid tune: --checkpoint: %s; the search stopped, nothing written\n",
                   checkpoint_error.c_str());
      return kExitFailure;
    }
    std::fprintf(stderr,
                 "fuzzypid tune: stopped by signal %d; the state after the last whole generation "
                 "is in %s: run the same command with --resume %s to continue (%s not written)\n",
                 static_cast<int>(g_stop_signal), t.checkpoint.c_str(), t.checkpoint.c_str(),
                 t.front_out.c_str());
    return 128 + static_cast<int>(g_stop_signal);
  }
  // Each point's record, as a single result's; points short of a required margin are left out.
  TuneOptions per_point = t;
  per_point.quiet = true;  // no margin line per point
  std::vector<tune::FrontPoint> kept;
  std::vector<cf::ControllerFile> kept_files;
  for (tune::FrontPoint& point : front->points) {
    char name[32];
    std::snprintf(name, sizeof name, "point_%03zu.toml", kept.size());
    const std::string out = (std::filesystem::path(t.front_out) / name).string();
    cf::ControllerFile file{point.controller, point.tuning, std::nullopt};
    const auto done = complete_record(t, out, family, opt, training, experiments, file, error);
    if (!done) {
      std::fprintf(stderr, "fuzzypid tune: certify: %s\n", error.c_str());
      return kExitFailure;
    }
    if (done->short_of_required) {
      std::fprintf(stderr,
                   "fuzzypid tune: warning: a front point below the required margins (disk %.3f) "
                   "is left out\n",
                   done->margins.disk_margin);
      continue;
    }
    if (!t.report_set.empty()) {
      // The validation values came from another set, not from conditions held back.
      file.tuning->validation_conditions = 0;
      file.tuning->validation_cost = std::numeric_limits<double>::quiet_NaN();
      file.controller.description += "; front validation on [" + t.report_set + "]";
    }
    kept.push_back(std::move(point));
    kept_files.push_back(std::move(file));
  }
  if (kept.empty()) {
    std::fprintf(stderr,
                 "fuzzypid tune: no point of the front kept the required margins; %s not "
                 "written\n",
                 t.front_out.c_str());
    return kExitFailure;
  }
  const bool validation = !kept.front().validation.empty();
  std::string csv = "point,file";
  for (const char* prefix : {"", "validation_"}) {
    if (*prefix != '\0' && !validation) continue;
    for (const tune::Metric m : fo.objectives)
      csv += std::string(",") + prefix + fuzzypid::name_of(tune::kMetricNames, m);
  }
  csv += '\n';
  for (std::size_t k = 0; k < kept.size(); ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "point_%03zu.toml", k);
    csv += std::to_string(k) + "," + name;
    char buf[40];
    for (const auto* values : {&kept[k].training, &kept[k].validation})
      for (const double v : *values) {
        std::snprintf(buf, sizeof buf, ",%.17g", v);
        csv += buf;
      }
    csv += '\n';
    std::FILE* f = out_set->add(name, error);
    const std::string text = cf::to_toml(kept_files[k]);
    if (f == nullptr || std::fwrite(text.data(), 1, text.size(), f) != text.size()) {
      std::fprintf(stderr, "fuzzypid tune: %s: %s\n", t.front_out.c_str(),
                   f == nullptr ? error.c_str() : std::strerror(errno != 0 ? errno : EIO));
      return kExitFailure;
    }
  }
  if (std::fwrite(csv.data(), 1, csv.size(), out_set->file(0)) != csv.size() ||
      !out_set->commit(error)) {
    std::fprintf(stderr, "fuzzypid tune: %s: %s\n", t.front_out.c_str(),
                 error.empty() ? std::strerror(errno != 0 ? errno : EIO) : error.c_str());
    return kExitFailure;
  }
  for (std::size_t k = 0; k < kept.size(); ++k) {
    std::printf("point %03zu:", k);
    for (std::size_t i = 0; i < fo.objectives.size(); ++i)
      std::printf(" %s %.6g%s", fuzzypid::name_of(tune::kMetricNames, fo.objectives[i]),
                  kept[k].training[i], i + 1 < fo.objectives.size() ? "," : "");
    if (validation) {
      std::printf(" (validation");
      for (std::size_t i = 0; i < fo.objectives.size(); ++i)
        std::printf(" %.6g", kept[k].validation[i]);
      std::printf(")");
    }
    std::printf("\n");
  }
  const double rate =
      front->wall_s > 0.0 ? static_cast<double>(front->evaluations) / front->wall_s : 0.0;
  std::printf("front of family %s: %zu points, %" PRIu64 " evaluations (population %" PRIu64
              ", %" PRIu64 " generations) in %.1f s, %.1f evaluations/s -> %s\n",
              controller::to_string(family), kept.size(), front->evaluations, front->population,
              front->generations, front->wall_s, rate, t.front_out.c_str());
  return kExitOk;
}

// True when the file `file` lies in the folder `dir` (both resolved as far as they exist).
bool lies_in(const std::string& dir, const std::string& file) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path folder = fs::weakly_canonical(fs::absolute(dir, ec), ec);
  const fs::path parent = fs::weakly_canonical(fs::absolute(file, ec).parent_path(), ec);
  return !ec && folder == parent;
}

// A result's worst figures over some of its runs, as sim_ab's metrics.csv gives them: each the
// largest over the runs' joints, with the joint (1-based) and the condition it came from.
struct Worst {
  double value = 0.0;
  std::size_t joint = 1;
  std::size_t run = 0;  // the condition's index
  std::string condition;
  void take(double v, std::size_t j, std::size_t k, const std::string& c) {
    if (!(v > value) && !condition.empty()) return;
    value = v;
    joint = j + 1;
    run = k;
    condition = c;
  }
};
struct RunFigures {
  std::size_t runs = 0;  // the runs the figures cover: those that ran to their end
  Worst error_after_1s_rad, reversals_pct, saturated_pct;
};

// The figures of `spec` on conditions[first, last), each on experiments.of(k), at the objective's
// divergence bound as the tuner ran them; a run that stopped early (diverged) is left out, its
// fault said elsewhere.
RunFigures figures_of(const sim::ExperimentSet& experiments,
                      const std::vector<sim::Condition>& conditions, std::size_t first,
                      std::size_t last, const controller::ControllerSpec& spec,
                      double divergence_rad) {
  RunFigures out;
  sim::RunLimits limits;
  limits.max_error_rad = divergence_rad;
  for (std::size_t k = first; k < last; ++k) {
    const sim::Experiment& ex = experiments.of(k);
    const sim::RunResult r = ex.run(conditions[k], spec, limits);
    if (!r.ok || r.diverged) continue;
    ++out.runs;
    const auto m = sim::run_metrics(r.rows, ex.options().tick_s);
    const auto d = sim::run_drive_metrics(r.rows);
    const std::string& name = conditions[k].name;
    for (std::size_t j = 0; j < robot::kNumJoints; ++j) {
      out.error_after_1s_rad.take(m[j].max_abs_error_after_1s_rad, j, k, name);
      out.reversals_pct.take(d[j].reversals_pct, j, k, name);
      out.saturated_pct.take(d[j].saturated_pct, j, k, name);
    }
  }
  return out;
}

// "V UNIT (joint J, CONDITION)", or "0 UNIT" when no joint reached above 0.
std::string said(const Worst& w, const char* format, const char* unit) {
  std::array<char, 64> v{};
  std::snprintf(v.data(), v.size(), format, w.value);
  std::string out = std::string(v.data()) + " " + unit;
  if (w.value > 0.0) out += " (joint " + std::to_string(w.joint) + ", " + w.condition + ")";
  return out;
}

// One line of the summary: "result on its N KIND runs: ..." (nothing when no run covers it).
void print_figures(const RunFigures& f, const char* kind) {
  if (f.runs == 0) return;
  std::printf(
      "result on its %zu %s run%s: |e| after 1 s up to %s; the command reverses on up to "
      "%s, the torque sits at a limit on up to %s\n",
      f.runs, kind, f.runs == 1 ? "" : "s", said(f.error_after_1s_rad, "%.3g", "rad").c_str(),
      said(f.reversals_pct, "%.1f", "% of a joint's ticks").c_str(),
      said(f.saturated_pct, "%.1f", "%").c_str());
}

int run_tune(const TuneOptions& t) {
  const bool front = !t.front_out.empty();
  const tune::Transport* transport = t.transport ? t.transport() : nullptr;
  // Ranks other than 0 serve runs only: they write, lock and print nothing.
  const bool writer = transport == nullptr || transport->rank == 0;
  const bool quiet = t.quiet || !writer;
  const std::string out_option = front ? "--front-out" : "--out";
  // "" when the outputs may be written by a run reading `inputs`, else why. A front's folder is
  // replaced whole, so it may hold no input at all.
  const auto refuse_outputs = [&](std::vector<std::string> inputs) -> std::string {
    if (!writer) return "";
    if (!front) return check_output_path(t.out, inputs);
    if (std::string bad = check_output_dir(t.front_out, {"front.csv"}, inputs); !bad.empty())
      return bad;
    for (const std::string& input : inputs)
      if (!input.empty() && lies_in(t.front_out, input))
        return "the front's folder " + t.front_out + " holds the input " + input +
               ", and it is replaced as a whole: write the front to another folder";
    if (t.checkpoint.empty()) return "";
    if (lies_in(t.front_out, t.checkpoint))
      return "--checkpoint " + t.checkpoint + " lies in the front's folder " + t.front_out +
             ", which is replaced as a whole: keep it elsewhere";
    // The checkpoint may be the state it resumes from.
    inputs.erase(std::remove(inputs.begin(), inputs.end(), t.resume), inputs.end());
    if (std::string bad = check_output_path(t.checkpoint, inputs); !bad.empty())
      return "--checkpoint: " + bad;
    return "";
  };
  // The outputs are checked before anything else: a refused output never costs the budget.
  if (const std::string bad = refuse_outputs(
          {t.conditions, t.base_file, t.init_file, t.resume, robot::default_urdf_path()});
      !bad.empty()) {
    std::fprintf(stderr, "fuzzypid tune: %s: %s\n", out_option.c_str(), bad.c_str());
    return kExitUsage;
  }
  // Held (locked) from here to the commit: a second run writing the same output is refused now,
  // not after both have spent their budgets and one result has replaced the other.
  std::string open_error;
  std::unique_ptr<OutputFile> out_file;
  std::unique_ptr<OutputSet> out_set;
  if (writer && !front) out_file = OutputFile::open(t.out, open_error, "tune");
  if (writer && front) {
    out_set = OutputSet::open(t.front_out, {"front.csv"}, open_error);
    if (out_set) out_set->replace_all_starting_with("point_");
  }
  if (writer && !out_file && !out_set) {
    std::fprintf(stderr, "fuzzypid tune: %s: %s\n", out_option.c_str(), open_error.c_str());
    return kExitFailure;
  }
  std::vector<tune::Stage> stages;
  if (!t.stages.empty()) {
    std::string bad;
    if (!parse_stages(t.stages, stages, bad)) {
      std::fprintf(stderr, "fuzzypid tune: --stages: %s\n", bad.c_str());
      return kExitUsage;
    }
  }
  controller::Family family{};
  if (!t.family_name.empty()) {
    family = *fuzzypid::parse_enum(controller::kFamilyNames, t.family_name);
  } else if (!stages.empty()) {
    family = stages.back().family;
  } else {
    std::fprintf(stderr, "fuzzypid tune: --family or --stages is required\n");
    return kExitUsage;
  }
  std::uint64_t total_budget = t.budget;
  if (!stages.empty()) {
    total_budget = 0;
    for (const tune::Stage& st : stages)
      total_budget += st.budget;
    if (total_budget > kMaxBudget) {
      std::fprintf(stderr,
                   "fuzzypid tune: --stages: the budgets sum to %" PRIu64
                   " evaluations, above the limit %" PRIu64 " of --budget\n",
                   total_budget, kMaxBudget);
      return kExitUsage;
    }
    if (stages.back().family != family) {
      std::fprintf(stderr, "fuzzypid tune: --family %s is not the last stage's (%s)\n",
                   t.family_name.c_str(), controller::to_string(stages.back().family));
      return kExitUsage;
    }
    if (t.budget_given && t.budget != total_budget) {
      std::fprintf(stderr,
                   "fuzzypid tune: --budget %" PRIu64 " is not the stages' total %" PRIu64 "\n",
                   t.budget, total_budget);
      return kExitUsage;
    }
  }
  // The rule-table options shape the search of a family with a rule table only.
  bool rule_table_stage = controller::family_traits(family).rule_table;
  std::string families = controller::to_string(family);
  for (std::size_t k = 0; k < stages.size(); ++k) {
    rule_table_stage = rule_table_stage || controller::family_traits(stages[k].family).rule_table;
    families = (k == 0 ? "" : families + ", ") + controller::to_string(stages[k].family);
  }
  if (const std::string bad = t.given.refuse_unused(
          {"--symmetry", "--partition", "--smoothness", "--monotone", "--unvisited",
           "--visit-threshold", "--cell-log10"},
          rule_table_stage, "a fuzzy-rules search (--family or a --stages stage)",
          (stages.empty() ? "--family is " : "the stages are ") + families);
      !bad.empty()) {
    std::fprintf(stderr, "fuzzypid tune: %s\n", bad.c_str());
    return kExitUsage;
  }
  if (const std::string bad =
          t.given.refuse_unused({"--chatter-limit"}, t.objective.chatter_weight > 0.0,
                                "a chatter weight above 0", "--chatter-weight is 0");
      !bad.empty()) {
    std::fprintf(stderr, "fuzzypid tune: %s\n", bad.c_str());
    return kExitUsage;
  }
  if (const std::string bad =
          t.given.refuse_unused({"--visit-threshold"}, t.unvisited == "seed", "--unvisited seed",
                                "--unvisited free searches every cell, visited or not");
      !bad.empty()) {
    std::fprintf(stderr, "fuzzypid tune: %s\n", bad.c_str());
    return kExitUsage;
  }
  tune::Options opt;
  opt.table = t.table;
  opt.table.symmetry = *fuzzypid::parse_enum(tune::kSymmetryNames, t.symmetry);
  opt.table.unvisited = *fuzzypid::parse_enum(tune::kUnvisitedNames, t.unvisited);
  opt.table.partition = t.partition == "tuned";
  opt.validation = t.validation;
  opt.search_filter = t.search_filter;
  opt.search_bandwidth = t.search_bandwidth;
  opt.family = family;
  opt.budget = t.budget;
  opt.seed = t.seed;
  opt.threads = t.threads;
  opt.population = t.population;
  opt.objective = t.objective;
  opt.base = controller::paper_pid();
  opt.base.description.clear();
  if (!t.base_file.empty()) {
    fuzzypid::FileError err;
    cf::ControllerFile base;
    if (!cf::load(t.base_file, base, err)) {
      std::fprintf(stderr, "fuzzypid tune: %s\n", err.to_string().c_str());
      return 1;
    }
    opt.base = base.controller;
    // The base's rule file is an input too (read relative to the base's folder).
    if (!opt.base.supervisor.rule_file.empty()) {
      const std::string rules =
          (std::filesystem::path(t.base_file).parent_path() / opt.base.supervisor.rule_file)
              .string();
      if (const std::string bad = refuse_outputs({rules}); !bad.empty()) {
        std::fprintf(stderr, "fuzzypid tune: %s: %s\n", out_option.c_str(), bad.c_str());
        return kExitUsage;
      }
    }
  }
  if (!t.init_file.empty()) {
    fuzzypid::FileError err;
    cf::ControllerFile init_file;
    if (!cf::load(t.init_file, init_file, err)) {
      std::fprintf(stderr, "fuzzypid tune: --init: %s\n", err.to_string().c_str());
      return 1;
    }
    const controller::ControllerSpec& init = init_file.controller;
    // The search starts here; the result keeps its units, PID options, bounds and rule base.
    const controller::Family first = stages.empty() ? family : stages.front().family;
    controller::ControllerSpec converted;
    std::string why;
    if (!tune::convert(init, first, converted, why)) {
      std::fprintf(stderr, "fuzzypid tune: --init %s: %s\n", t.init_file.c_str(), why.c_str());
      return 1;
    }
    if (t.base_file.empty()) opt.base = init;
    opt.init = init;
  }
  const std::vector<tune::SearchBox> defaults = tune::default_box(family);
  for (const std::string& text : t.boxes) {
    tune::SearchBox b;
    if (!parse_box(text, b)) {
      std::fprintf(
          stderr,
          "fuzzypid tune: --box %s: expected NAME=MIN:MAX (log10, -300 <= MIN <= MAX <= 300)\n",
          text.c_str());
      return 2;
    }
    // Table cells are named once visits are known.
    bool found = controller::family_traits(family).rule_table;
    for (const auto& d : defaults)
      if (d.name == b.name) found = true;
    opt.box.push_back(b);
    if (!found) {
      std::fprintf(stderr, "fuzzypid tune: --box: the %s family has no parameter '%s'\n",
                   controller::to_string(family), b.name.c_str());
      return 2;
    }
  }

  sim::ConditionFile file;
  fuzzypid::FileError err;
  if (!sim::load_conditions(t.conditions, file, err)) {
    std::fprintf(stderr, "fuzzypid tune: %s\n", err.to_string().c_str());
    return 1;
  }
  const sim::ConditionSet* training = file.find(t.set);
  if (training == nullptr) {
    std::fprintf(stderr, "fuzzypid tune: %s has no set '%s' (it has: %s)\n", t.conditions.c_str(),
                 t.set.c_str(), file.set_names().c_str());
    return 1;
  }
  // --report-set: its conditions follow the training set's as a front's validation conditions,
  // run on the final front only; the search never sees them.
  sim::ConditionSet searched = *training;
  if (!t.report_set.empty()) {
    const sim::ConditionSet* report = file.find(t.report_set);
    if (report == nullptr) {
      std::fprintf(stderr, "fuzzypid tune: %s has no set '%s' (it has: %s)\n", t.conditions.c_str(),
                   t.report_set.c_str(), file.set_names().c_str());
      return 1;
    }
    searched.conditions.insert(searched.conditions.end(), report->conditions.begin(),
                               report->conditions.end());
  }
  // The robots and paths the conditions name are inputs too: --out must not replace them.
  for (const sim::Condition& c : searched.conditions)
    for (const std::string& input : {c.robot.urdf, c.robot.path})
      if (!input.empty())
        if (const std::string bad = refuse_outputs({input}); !bad.empty()) {
          std::fprintf(stderr, "fuzzypid tune: %s: %s\n", out_option.c_str(), bad.c_str());
          return kExitUsage;
        }
  // Each training condition on its own robot and path (keys urdf, path, tick_ms, ...).
  sim::ExperimentOptions eo;
  eo.tick_s = opt.base.units.tick_s;
  std::string error;
  const auto experiments = sim::ExperimentSet::create(searched.conditions, eo, error);
  if (!experiments) {
    std::fprintf(stderr, "fuzzypid tune: %s\n", error.c_str());
    return 1;
  }
  for (std::size_t k = 0; k < experiments->size(); ++k) {
    if (!quiet) print_robot_note("fuzzypid tune", experiments->experiment(k));
    if (writer) print_model_notes("fuzzypid tune", experiments->experiment(k));
  }
  for (std::size_t k = 0; writer && k < training->conditions.size(); ++k)
    warn_about_payload("fuzzypid tune", experiments->of(k), training->conditions[k]);

  if (t.validation >= training->conditions.size()) {
    std::fprintf(stderr,
                 "fuzzypid tune: --validation %" PRIu64
                 " leaves no training condition (set %s has %zu)\n",
                 t.validation, t.set.c_str(), training->conditions.size());
    return kExitUsage;
  }
  // The conditions the search trains on; the last t.validation of the set validate.
  const std::size_t trained = training->conditions.size() - static_cast<std::size_t>(t.validation);

  if (!quiet) {
    std::fprintf(stderr,
                 "fuzzypid tune: family %s, %zu training conditions (set %s), budget %" PRIu64
                 ", seed %" PRIu64 ", %u threads\n",
                 controller::to_string(family), trained, t.set.c_str(), total_budget, t.seed,
                 t.threads);
    if (t.validation != 0)
      std::fprintf(stderr,
                   "fuzzypid tune: the last %" PRIu64
                   " conditions of the set held back for validation\n",
                   t.validation);
    double last = -1.0;
    opt.progress = [last](const tune::Progress& p) mutable {
      if (p.elapsed_s - last < 2.0 && p.evaluations < p.budget) return;
      last = p.elapsed_s;
      const double rate = p.elapsed_s > 0 ? static_cast<double>(p.evaluations) / p.elapsed_s : 0;
      const double eta = rate > 0 ? static_cast<double>(p.budget - p.evaluations) / rate : 0.0;
      std::fprintf(stderr,
                   "fuzzypid tune: %8" PRIu64 "/%" PRIu64
                   " evaluations, best cost %.6g, %.1f evaluations/s, ETA %.0f s\n",
                   p.evaluations, p.budget, p.best_cost, rate, eta);
    };
  }
  opt.transport = transport;
  if (front) {
    opt.validation = searched.conditions.size() - training->conditions.size() + t.validation;
    return run_front(t, family, opt, *training, searched, *experiments, out_set.get());
  }
  auto result = stages.empty()
                    ? tune::tune(*experiments, training->conditions, opt, error)
                    : tune::tune_staged(*experiments, training->conditions, stages, opt, error);
  if (!result) {
    std::fprintf(stderr, "fuzzypid tune: %s\n", error.c_str());
    return 2;
  }
  if (result->served) return kExitOk;
  cf::ControllerFile tuned{result->controller, result->tuning, std::nullopt};
  std::optional<Completion> done =
      complete_record(t, t.out, family, opt, *training, *experiments, tuned, error);
  if (!done) {
    std::fprintf(stderr, "fuzzypid tune: certify: %s\n", error.c_str());
    return 1;
  }
  if (done->short_of_required) {
    const sim::MarginSummary& m = done->margins;
    std::fprintf(stderr,
                 "fuzzypid tune: no candidate within the budget kept the required margins "
                 "(the best: disk %.3f, gain %.2f dB, phase %.1f deg, delay %.1f ms); %s not "
                 "written\n",
                 m.disk_margin, m.gain_margin_db, m.phase_margin_deg, m.delay_margin_ms,
                 t.out.c_str());
    return 1;
  }
  if (done->record_short_of_required) {
    const sim::MarginSummary& m = done->margins;
    std::fprintf(stderr,
                 "fuzzypid tune: warning: the result kept the required margins as the search "
                 "screened them (its training plants, a %zu-point grid of the supervisor's "
                 "inputs), but not over every plant its [margins] record covers (validation "
                 "plants included, a %zu-point grid): disk %.3f, gain %.2f dB, phase %.1f deg, "
                 "delay %.1f ms (docs/margins.md)\n",
                 tune::screening_options(0.0).grid_points, sim::CertifyOptions{}.grid_points,
                 m.disk_margin, m.gain_margin_db, m.phase_margin_deg, m.delay_margin_ms);
  }
  const std::string text = cf::to_toml(tuned);
  if (std::fwrite(text.data(), 1, text.size(), out_file->file()) != text.size()) {
    std::fprintf(stderr, "fuzzypid tune: cannot write %s: %s\n", t.out.c_str(),
                 std::strerror(errno != 0 ? errno : EIO));
    return 1;
  }
  if (!out_file->commit(error)) {
    std::fprintf(stderr, "fuzzypid tune: %s\n", error.c_str());
    return 1;
  }
  for (const tune::BoundHit& h : tuned.tuning->on_bound) {
    const auto& box = tuned.tuning->box;
    const auto b = std::find_if(box.begin(), box.end(),
                                [&](const tune::SearchBox& s) { return s.name == h.name; });
    std::fprintf(stderr,
                 "fuzzypid tune: warning: %s ended on the %s of its box (log10 %.4g in [%.4g, "
                 "%.4g]): the optimum may lie outside; widen it with --box %s=MIN:MAX and "
                 "re-tune (recorded as on_bound in %s)\n",
                 h.name.c_str(), h.upper ? "top" : "bottom", h.log10,
                 b != box.end() ? b->log10_min : h.log10, b != box.end() ? b->log10_max : h.log10,
                 h.name.c_str(), t.out.c_str());
  }
  const double rate = static_cast<double>(result->evaluations) / result->wall_s;
  const auto& stage_records = tuned.tuning->stages;
  for (std::size_t k = 0; k < stage_records.size(); ++k) {
    const auto& st = stage_records[k];
    const double wall = k < result->stage_wall_s.size() ? result->stage_wall_s[k] : 0.0;
    std::printf("stage %s: %" PRIu64 " evaluations (budget %" PRIu64
                ") in %.1f s, %.1f evaluations/s, training cost %.6g, validation cost %.6g\n",
                controller::to_string(st.family), st.evaluations, st.budget, wall,
                wall > 0.0 ? static_cast<double>(st.evaluations) / wall : 0.0, st.training_cost,
                st.validation_cost);
  }
  std::printf("family %s: %" PRIu64 " evaluations (budget %" PRIu64
              ") in %.1f s, %.1f "
              "evaluations/s (%.0f condition runs/s), training cost %.6g (ITAE %.6g, overshoot "
              "penalty %.6g, chatter penalty %.6g, effort penalty %.6g, regulariser %.6g, %zu "
              "faulted runs)",
              controller::to_string(family), result->evaluations, total_budget, result->wall_s,
              rate, rate * static_cast<double>(trained), result->cost.total, result->cost.itae,
              result->cost.overshoot_penalty, result->cost.chatter_penalty,
              result->cost.effort_penalty, result->penalty, result->cost.faulted_runs);
  if (result->validation) std::printf(", validation cost %.6g", result->validation->total);
  std::printf(" -> %s\n", t.out.c_str());
  // What a drive engineer looks at first, on the runs the result was tuned and validated on: how
  // far off the path it stays once the start error is gone, how it rings, how it saturates.
  const double divergence = opt.objective.divergence_rad;
  const RunFigures on_training =
      figures_of(*experiments, training->conditions, 0, trained, result->controller, divergence);
  print_figures(on_training, "training");
  print_figures(figures_of(*experiments, training->conditions, trained, training->conditions.size(),
                           result->controller, divergence),
                "validation");
  // A result that stays off the path by half the divergence bound on its own training runs is
  // one harder condition away from a fault (a heavier tool, a faster path): said, not refused.
  if (on_training.runs > 0 && result->cost.faulted_runs == 0 &&
      on_training.error_after_1s_rad.value > 0.5 * divergence) {
    const Worst& w = on_training.error_after_1s_rad;
    const sim::Experiment& ex = experiments->of(w.run);
    const robot::PlantConfig plant = ex.plant_config(training->conditions[w.run]);
    // What the worst run's set-up leaves out of the remedies a loop holds the arm closer with.
    std::array<char, 32> tick_ms{};
    std::snprintf(tick_ms.data(), tick_ms.size(), "%g", ex.options().tick_s * 1e3);
    std::vector<std::string> remedies{"a shorter tick (tick_ms; this one is " +
                                      std::string(tick_ms.data()) + " ms)"};
    if (std::all_of(plant.armature_kgm2.begin(), plant.armature_kgm2.end(),
                    [](double a) { return a == 0.0; }))
      remedies.emplace_back("the motors' reflected inertia (armature, 0 here)");
    if (plant.gravity && !result->controller.feedforward.gravity)
      remedies.emplace_back("a --base with a gravity feed-forward");
    std::string consider = remedies.front();
    for (std::size_t k = 1; k < remedies.size(); ++k)
      consider += (k + 1 == remedies.size() ? " or " : ", ") + remedies[k];
    std::fprintf(stderr,
                 "fuzzypid tune: warning: the result is still %.3g rad off the path after the "
                 "first second of training condition %s (joint %zu), more than half of "
                 "--divergence (%g rad): a little more load or speed than training had may "
                 "fault. Consider %s (docs/your_robot.md)\n",
                 w.value, w.condition.c_str(), w.joint, divergence, consider.c_str());
  }
  // A result that faults where it was tuned or validated is no controller to load into a drive:
  // said on stderr, and exit 1 unless --allow-faults (the file is written either way).
  const std::size_t validation_faults = result->validation ? result->validation->faulted_runs : 0;
  if (result->cost.faulted_runs + validation_faults > 0) {
    const std::string validation_runs = t.validation > 0
                                            ? " and " + std::to_string(validation_faults) + " of " +
                                                  std::to_string(t.validation) + " validation"
                                            : std::string();
    std::fprintf(stderr,
                 "fuzzypid tune: the result faults on %zu of %zu training%s runs (|e| > "
                 "--divergence, a joint outside its limits or a controller fault; `sim_ab "
                 "--conditions %s --set %s --controller %s` names them); a larger --budget, "
                 "another --seed or a wider --box may find a stable one%s\n",
                 result->cost.faulted_runs, trained, validation_runs.c_str(), t.conditions.c_str(),
                 t.set.c_str(), t.out.c_str(), t.allow_faults ? " (--allow-faults: exit 0)" : "");
    if (!t.allow_faults) return 1;
  }
  return 0;
}

struct ExportOptions {
  std::string in, out, ns = "fuzzypid_controller";
  bool out_given = false;  // --out '' is refused, not stdout
  RobotOptions robot;      // the plant whose J^ and torque limits the header records
  // The conditions the certificate covers (empty: the robot options' nominal plant on its path).
  std::string conditions;
  std::string set = "held-out";
  bool allow_uncertified = false;
};

// The certificate of `spec` over --conditions [--set] or, without them, over the nominal plant of
// the robot options, as `fuzzypid certify` computes it (the conditions' largest delay).
std::optional<controller::MarginRecord> margins_for_header(const ExportOptions& o,
                                                           const cf::ControllerFile& file,
                                                           std::string& error) {
  const controller::ControllerSpec& spec = file.controller;
  std::vector<sim::Condition> conditions;
  if (!o.conditions.empty()) {
    sim::ConditionFile file;
    fuzzypid::FileError err;
    if (!sim::load_conditions(o.conditions, file, err)) {
      error = err.to_string();
      return std::nullopt;
    }
    const sim::ConditionSet* set = file.find(o.set);
    if (set == nullptr) {
      error = "--set: " + o.conditions + " has no set '" + o.set +
              "' (it has: " + file.set_names() + ")";
      return std::nullopt;
    }
    conditions = set->conditions;
  } else {
    sim::Condition c;
    o.robot.apply(c);
    if (!o.robot.tick_given && file.tuning && file.tuning->tick_s > 0.0)
      c.robot.tick_s = file.tuning->tick_s;
    if (const std::string bad = c.validate(); !bad.empty()) {
      error = bad;
      return std::nullopt;
    }
    conditions.push_back(c);
  }
  const auto experiments = sim::ExperimentSet::create(conditions, sim::ExperimentOptions{}, error);
  if (!experiments) return std::nullopt;
  sim::CertifyOptions co;
  co.delay_s = sim::largest_delay_s(conditions);
  const auto cert = sim::certify(spec, conditions, *experiments, co, error);
  if (!cert) return std::nullopt;
  controller::MarginRecord r = sim::margin_record(*cert);
  r.conditions = o.conditions.empty() ? "the nominal plant of the robot options" : o.conditions;
  r.set = o.conditions.empty() ? "-" : o.set;
  return r;
}

// J^ and the torque limits of the plant `o.robot` names (the bundled ER50-C20 on the section 6
// line by default), as sim_ab simulates it.
std::optional<fuzzypid::codegen::PlantRecord> plant_record(const ExportOptions& o,
                                                           const cf::ControllerFile& file,
                                                           std::string& error) {
  sim::Condition c;
  o.robot.apply(c);
  if (!o.robot.tick_given && file.tuning && file.tuning->tick_s > 0.0)
    c.robot.tick_s = file.tuning->tick_s;
  if (const std::string bad = c.validate(); !bad.empty()) {
    error = bad;
    return std::nullopt;
  }
  const auto ex = sim::Experiment::create(c.robot, sim::ExperimentOptions{}, error);
  if (!ex) return std::nullopt;
  fuzzypid::codegen::PlantRecord p;
  p.robot = (c.robot.urdf.empty() ? std::string("the bundled ER50-C20") : c.robot.urdf) +
            ", path " +
            (c.robot.path.empty() ? std::string("the section 6 line A -> B") : c.robot.path);
  for (std::size_t i = 0; i < robot::kNumJoints; ++i) {
    p.nominal_inertia_kgm2[i] = ex->nominal_inertia()[i];
    p.torque_limit_nm[i] = ex->torque_limit(c)[i];
  }
  return p;
}

int run_export_header(const ExportOptions& o) {
  const std::string& in = o.in;
  const std::string& out = o.out;
  const std::string& ns = o.ns;
  if (o.out_given) {
    if (const std::string bad = check_output_path(out, {in}); !bad.empty()) {
      std::fprintf(stderr, "fuzzypid export-header: --out: %s\n", bad.c_str());
      return kExitUsage;
    }
  }
  cf::ControllerFile file;
  fuzzypid::FileError err;
  if (!cf::load(in, file, err)) {
    std::fprintf(stderr, "fuzzypid export-header: %s\n", err.to_string().c_str());
    return 1;
  }
  const controller::ControllerSpec& spec = file.controller;
  if (const std::string bad = fuzzypid::codegen::check_float_range(spec); !bad.empty()) {
    std::fprintf(stderr, "fuzzypid export-header: %s: %s\n", in.c_str(), bad.c_str());
    return 1;
  }
  if (file.tuning && o.robot.setup.urdf.empty())
    for (const auto& f : file.tuning->trained_on)
      if (f.kind == "urdf")
        std::fprintf(stderr,
                     "fuzzypid export-header: warning: %s was tuned on %s; the header's J^ and "
                     "torque limits are the bundled ER50-C20's (give --urdf and --path)\n",
                     in.c_str(), f.file.c_str());
  std::string plant_error;
  const auto plant = plant_record(o, file, plant_error);
  if (!plant) {
    std::fprintf(stderr, "fuzzypid export-header: %s\n", plant_error.c_str());
    return 1;
  }
  const auto margins = margins_for_header(o, file, plant_error);
  if (!margins) {
    std::fprintf(stderr, "fuzzypid export-header: certify: %s\n", plant_error.c_str());
    return 1;
  }
  if (!margins->certified) {
    std::fprintf(stderr, "fuzzypid export-header: %s: %s over %s%s\n", in.c_str(),
                 margins->verdict.c_str(), margins->conditions.c_str(),
                 o.allow_uncertified ? " (written: --allow-uncertified)"
                                     : "; nothing written (--allow-uncertified writes it anyway, "
                                       "with kCertified = false)");
    if (!o.allow_uncertified) return 1;
  }
  const std::string text = fuzzypid::codegen::export_header(spec, ns, in, &*plant, &*margins);
  if (out.empty()) {
    std::fputs(text.c_str(), stdout);
    return std::ferror(stdout) ? 1 : 0;
  }
  if (const std::string bad = write_output_file(out, text, "export-header"); !bad.empty()) {
    std::fprintf(stderr, "fuzzypid export-header: %s\n", bad.c_str());
    return 1;
  }
  return 0;
}

}  // namespace

void add_tune_command(CLI::App& app, std::function<int()>& run) {
  auto t = std::make_shared<TuneOptions>();
  CLI::App* cmd = app.add_subcommand(
      "tune",
      "Tune a controller family on a training set of conditions (pagmo2 self-adaptive "
      "differential evolution, log10 search boxes, hard evaluation budget) and write the result "
      "as a controller file (docs/tuning.md). Progress goes to stderr.");
  std::vector<std::string> family_names;
  family_names.reserve(controller::kFamilyNames.size());
  for (const auto& e : controller::kFamilyNames)
    family_names.emplace_back(e.name);
  cmd->add_option("--family", t->family_name,
                  "controller family (" + fuzzypid::names_of(controller::kFamilyNames) +
                      "); with --stages, the last stage's")
      ->check(CLI::IsMember(family_names));
  cmd->add_option("--stages", t->stages,
                  "staged tuning, FAMILY:BUDGET,... (e.g. pid:8000,scheduled:24000,"
                  "fuzzy-rules:32000): each stage starts from the last one's result converted "
                  "exactly; the budgets add up to the total");
  cmd->add_option("--init", t->init_file,
                  "controller file the search starts from (one member of the first generation), "
                  "converted exactly into the (first stage's) family: pid -> scheduled -> "
                  "fuzzy-rules");
  cmd->add_option("--validation", t->validation,
                  "hold back the last N conditions of the set: never trained on, they choose the "
                  "result among the search's best points and among stages (default 0)")
      ->check(unsigned_in(0, 1000000));
  cmd->add_option("--symmetry", t->symmetry,
                  "fuzzy-rules: table symmetry, even (T(+-x, +-y) equal), odd (log T(-x, -y) = "
                  "-log T(x, y)) or none (default even)")
      ->check(CLI::IsMember({"even", "odd", "none"}));
  cmd->add_option("--partition", t->partition,
                  "fuzzy-rules: search the inner set centers too (tuned: ordered, symmetric) or "
                  "keep the start's (fixed) (default tuned)")
      ->check(CLI::IsMember({"tuned", "fixed"}));
  cmd->add_option("--smoothness", t->table.smoothness,
                  "fuzzy-rules: weight of the squared log10 differences of neighbouring cells "
                  "(default 0)")
      ->check(finite_in(0.0, 1e9));
  cmd->add_option("--monotone", t->table.monotone,
                  "fuzzy-rules: weight of the squared decreases of the gain ratio along rows and "
                  "columns, outwards in the schedule's direction (default 0)")
      ->check(finite_in(0.0, 1e9));
  cmd->add_option("--unvisited", t->unvisited,
                  "fuzzy-rules: cells the start's training runs never reach are held at the "
                  "start's values (seed) or searched (free) (default seed)")
      ->check(CLI::IsMember({"seed", "free"}));
  cmd->add_option("--visit-threshold", t->table.visit_threshold,
                  "fuzzy-rules: a node is visited above this share of the firing weight "
                  "(default 1e-4)")
      ->check(finite_in(0.0, 0.5));
  cmd->add_option("--cell-log10", t->table.cell_log10,
                  "fuzzy-rules: each cell's box, log10 T in [-X, X] (default 1)")
      ->check(finite_in(1e-3, 10.0));
  cmd->add_option("--conditions", t->conditions,
                  "condition-set file (TOML); each condition may name its robot, path, tick and "
                  "plant (keys urdf, path, tick_ms, payload_kg, armature, dynamics, gravity; "
                  "docs/your_robot.md)")
      ->required();
  cmd->add_option("--set", t->set, "the training set's name (default training)");
  CLI::Option* budget = cmd->add_option("--budget", t->budget,
                                        "objective evaluations, never exceeded (default 16000)")
                            ->check(unsigned_in(14, kMaxBudget));
  cmd->add_option("--seed", t->seed, "random seed (default 1)")->check(unsigned_in(0, 4294967295u));
  cmd->add_option("--threads", t->threads,
                  "threads evaluating the conditions (default: all cores; the result does not "
                  "depend on it)")
      ->check(unsigned_in(1, 256));
  cmd->add_option("--population", t->population,
                  "population size (default 5 x parameters, at least 20)")
      ->check(unsigned_in(7, 100000));
  CLI::Option* out = cmd->add_option("--out", t->out, "controller file to write");
  CLI::Option* objectives =
      cmd->add_option("--objectives", t->objectives,
                      "tune a Pareto front over 2 to 5 of itae, effort, chatter, overshoot and "
                      "margin, comma-separated (pagmo2's NSGA-II; docs/tuning.md, \"Fronts\")")
          ->check([](const std::string& text) {
            const std::size_t n = parse_objectives(text).size();
            return n >= 2 ? std::string()
                          : "expected 2 to 5 distinct objectives of " +
                                fuzzypid::names_of(tune::kMetricNames) + ", comma-separated";
          });
  CLI::Option* front_out =
      cmd->add_option("--front-out", t->front_out,
                      "with --objectives: the folder to write the front to (front.csv and one "
                      "controller file per point, replaced as a whole)")
          ->excludes(out);
  CLI::Option* checkpoint =
      cmd->add_option("--checkpoint", t->checkpoint,
                      "with --objectives: write the search's state to this file after every "
                      "generation (atomically); SIGINT or SIGTERM then stop the search after the "
                      "generation under way, its state saved")
          ->needs(objectives);
  cmd->add_option("--report-set", t->report_set,
                  "with --objectives: also run the final front on this set of --conditions (the "
                  "held-out one, say), reported as its validation columns; the search never sees "
                  "it")
      ->needs(objectives)
      ->excludes("--validation");
  cmd->add_option("--resume", t->resume,
                  "with --objectives: continue the search whose state this checkpoint holds "
                  "(the same options; it may also be --checkpoint's file)")
      ->needs(objectives);
  objectives->needs(front_out);
  front_out->needs(objectives);
  (void)checkpoint;
  cmd->add_option("--base", t->base_file,
                  "controller file whose units, PID options, bounds and rule base the result "
                  "keeps (default: the paper's, acceleration units per tick at 0.05 s)");
  cmd->add_option("--overshoot-bound", t->objective.overshoot_bound_pct,
                  "overshoot allowed without penalty, % (default 20)")
      ->check(finite_in(0.0, 1e6));
  cmd->add_option("--overshoot-weight", t->objective.overshoot_weight,
                  "cost per percentage point above the bound, per joint (default 0.1)")
      ->check(finite_in(0.0, 1e9));
  cmd->add_option("--fault-cost", t->objective.fault_cost,
                  "cost of a run that faults, diverges or gives non-finite ITAE (default 1000)")
      ->check(finite_in(0.0, 1e12));
  cmd->add_option("--chatter-weight", t->objective.chatter_weight,
                  "cost per unit of each joint's command reversal share (0..1: the share of ticks "
                  "on which the command's change reverses) above --chatter-limit (default 300; "
                  "docs/tuning.md, \"Chatter\")")
      ->check(finite_in(0.0, 1e9));
  cmd->add_option("--chatter-limit", t->objective.chatter_limit_pct,
                  "reversal share per joint and run, %, that costs nothing: the chatter term "
                  "counts only the share above it (default 5; 0: every reversal costs)")
      ->check(finite_in(0.0, 100.0));
  cmd->add_option("--effort-weight", t->objective.effort_weight,
                  "cost per unit of each joint's RMS command over its limit (0..1) (default 0)")
      ->check(finite_in(0.0, 1e9));
  cmd->add_option("--min-disk-margin", t->objective.min_disk_margin,
                  "every candidate keeps at least this disk margin alpha on every joint over the "
                  "training plants (e.g. 0.5: +-4.4 dB, +-28 deg; docs/margins.md); below it a "
                  "candidate is infeasible (default 0: no requirement)")
      ->check(finite_in(0.0, 2.0));
  cmd->add_option("--min-gain-margin", t->objective.min_gain_margin_db,
                  "the same for the upper gain margin, dB (default 0: none)")
      ->check(finite_in(0.0, 100.0));
  cmd->add_option("--min-phase-margin", t->objective.min_phase_margin_deg,
                  "the same for the phase margin, degrees (default 0: none)")
      ->check(finite_in(0.0, 180.0));
  cmd->add_option("--min-delay-margin", t->objective.min_delay_margin_ms,
                  "the same for the delay margin, ms (default 0: none)")
      ->check(finite_in(0.0, 1e6));
  cmd->add_option("--divergence", t->objective.divergence_rad,
                  "a run diverged once any |e| exceeds this, rad (default 1)")
      ->check(finite_in(1e-9, 1e3));
  cmd->add_option("--box", t->boxes,
                  "search box of one parameter in log10, NAME=MIN:MAX (repeatable; defaults in "
                  "docs/tuning.md)");
  cmd->add_flag("--search-filter,!--keep-filter", t->search_filter,
                "search the derivative filter's time constant Tf too (parameter tf, log10 s in "
                "[-3, 0] at a 50 ms tick; default), and with a start whose derivative is "
                "\"observer\" its bandwidth (observer_hz, log10 Hz in [-1, 1]); or keep both");
  cmd->add_flag("--per-joint-bandwidth", t->search_bandwidth,
                "search a bandwidth scale for each of joints 2-6 relative to joint 1 (parameters "
                "bandwidth_j2 .. bandwidth_j6, log10 in [-1, 1]): joint i gets Kp s^2, Ki s^3, "
                "Kd s and Tf / s (docs/tuning.md, \"Per-joint bandwidth\"); without it the "
                "result keeps the start's scales");
  cmd->add_flag("--quiet", t->quiet, "no progress on stderr");
  cmd->add_flag("--allow-faults", t->allow_faults,
                "a result that faults on some of its training or validation runs (|e| beyond "
                "--divergence, a joint outside its limits, a controller fault) is written and "
                "warned of, and exits 0 (else 1)");
#if FUZZYPID_HAVE_MPI
  t->transport = mpi_transport;
#endif
  cmd->callback([&run, t, budget, cmd, out, front_out] {
    if (out->count() == 0 && front_out->count() == 0)
      throw CLI::RequiredError("--out or --objectives with --front-out");
    if (front_out->count() > 0 && !t->stages.empty())
      throw CLI::ValidationError("--stages",
                                 "a front tunes one family: give --family, not --stages");
    t->budget_given = budget->count() > 0;
    t->given = GivenOptions(*cmd);
    run = [t] { return run_tune(*t); };
  });
}

void add_export_header_command(CLI::App& app, std::function<int()>& run) {
  auto o = std::make_shared<ExportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "export-header",
      "Write a controller file as a self-contained C++ header of constexpr configuration (no "
      "parser needed on the target), with its stability margins and certificate (as `fuzzypid "
      "certify` computes them); an uncertified controller is refused unless "
      "--allow-uncertified.");
  cmd->add_option("file", o->in, "controller file (TOML)")->required();
  CLI::Option* out = cmd->add_option("--out", o->out, "header to write (default: stdout)");
  cmd->add_option("--namespace", o->ns,
                  "namespace of the generated code: C++ identifiers joined by ::, no keyword or "
                  "reserved name (default fuzzypid_controller)")
      ->check([](const std::string& s) { return fuzzypid::codegen::check_namespace(s); });
  CLI::Option* conditions =
      cmd->add_option("--conditions", o->conditions,
                      "certify over this condition file's set instead of the nominal plant of the "
                      "robot options (the header's J^ and limits still come from those)")
          ->option_text("FILE");
  CLI::Option* set = cmd->add_option("--set", o->set, "the set of --conditions (default held-out)")
                         ->option_text("NAME");
  cmd->add_flag("--allow-uncertified", o->allow_uncertified,
                "write the header of a controller that is not certified (kCertified = false)");
  add_robot_options(*cmd, o->robot, true);
  cmd->callback([&run, o, out, conditions, set] {
    if (const std::string bad = check_robot_options(o->robot); !bad.empty())
      throw CLI::ValidationError(bad);
    if (set->count() > 0 && conditions->count() == 0)
      throw CLI::ValidationError("--set", "needs --conditions");
    // The header's J^ and torque limits are the nominal model's: the plant's payload, dynamics,
    // gravity and joint effects change neither, so those options would do nothing.
    if (o->robot.payload_kg || o->robot.dynamics || o->robot.gravity ||
        o->robot.effects != sim::JointEffects{})
      throw CLI::ValidationError(
          "export-header takes only the robot options that choose the nominal model (--urdf, "
          "--base-link, --tip-link, --path, --tick-ms, --armature, --ik-seed): the payload, the "
          "dynamics, gravity and the joint effects change neither J^ nor the torque limits");
    o->out_given = out->count() > 0;
    run = [o] { return run_export_header(*o); };
  });
}

}  // namespace fuzzypid::cli
