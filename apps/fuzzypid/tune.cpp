// `fuzzypid tune`: robust tuning of a controller family on a condition set (docs/tuning.md), and
// `fuzzypid export-header`: a controller file as a self-contained C++ header.
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid/controller_file/export_header.hpp"
#include "fuzzypid/robot/path.hpp"
#include "fuzzypid/robot/robot_model.hpp"
#include "fuzzypid/sim/condition_set.hpp"
#include "fuzzypid/sim/experiment.hpp"
#include "fuzzypid/tune/tune.hpp"

namespace fuzzypid::cli {

namespace {

namespace cf = controller_file;

// CLI11 reports usage errors itself; 0 after --help, 2 after a usage error, -1 to go on.
int parse_or_exit(CLI::App& app, int argc, char** argv, const char* name) {
  std::vector<const char*> args{name};
  for (int k = 0; k < argc; ++k)
    args.push_back(argv[k]);
  try {
    app.parse(static_cast<int>(args.size()), args.data());
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help().c_str(), stdout);
    return 0;
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "%s: %s (see --help)\n", name, e.what());
    return 2;
  }
  return -1;
}

bool parse_box(const std::string& text, cf::SearchBox& box) {
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
  return std::isfinite(box.log10_min) && std::isfinite(box.log10_max) &&
         box.log10_min <= box.log10_max;
}

}  // namespace

int run_tune(int argc, char** argv) {
  CLI::App app{
      "fuzzypid tune: tune a controller family on a training set of conditions (pagmo2 "
      "self-adaptive differential evolution, log10 search boxes, hard evaluation budget) and "
      "write the result as a controller file. Progress goes to stderr.",
      "fuzzypid tune"};
  app.get_formatter()->column_width(36);
  std::string family_name, conditions, set = "training", out, base_file;
  std::uint64_t budget = 16000, seed = 1, population = 0;
  unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  cf::Objective objective;
  std::vector<std::string> boxes;
  bool quiet = false;
  std::vector<std::string> family_names;
  for (const auto& e : cf::kFamilyNames)
    family_names.emplace_back(e.name);
  app.add_option("--family", family_name,
                 "controller family (" + cf::names_of(cf::kFamilyNames) + ")")
      ->required()
      ->check(CLI::IsMember(family_names));
  app.add_option("--conditions", conditions, "condition-set file (TOML)")->required();
  app.add_option("--set", set, "the training set's name (default training)");
  app.add_option("--budget", budget, "objective evaluations, never exceeded (default 16000)")
      ->check(CLI::Range(std::uint64_t{14}, std::uint64_t{100000000}));
  app.add_option("--seed", seed, "random seed (default 1)")
      ->check(CLI::Range(std::uint64_t{0}, std::uint64_t{4294967295u}));
  app.add_option("--threads", threads,
                 "threads evaluating the conditions (default: all cores; the result does not "
                 "depend on it)")
      ->check(CLI::Range(1u, 256u));
  app.add_option("--population", population,
                 "population size (default 5 x parameters, at least 20)")
      ->check(CLI::Range(std::uint64_t{7}, std::uint64_t{100000}));
  app.add_option("--out", out, "controller file to write")->required();
  app.add_option("--base", base_file,
                 "controller file whose units, PID options, bounds and rule base the result "
                 "keeps (default: the paper's, acceleration units per tick at 0.05 s)");
  app.add_option("--overshoot-bound", objective.overshoot_bound_pct,
                 "overshoot allowed without penalty, % (default 20)")
      ->check(CLI::Range(0.0, 1e6));
  app.add_option("--overshoot-weight", objective.overshoot_weight,
                 "cost per percentage point above the bound, per joint (default 0.1)")
      ->check(CLI::Range(0.0, 1e9));
  app.add_option("--fault-cost", objective.fault_cost,
                 "cost of a run that faults, diverges or gives non-finite ITAE (default 1000)")
      ->check(CLI::Range(0.0, 1e12));
  app.add_option("--divergence", objective.divergence_rad,
                 "a run diverged once any |e| exceeds this, rad (default 1)")
      ->check(CLI::Range(1e-9, 1e3));
  app.add_option("--box", boxes,
                 "search box of one parameter in log10, NAME=MIN:MAX (repeatable; defaults in "
                 "docs/tuning.md)");
  app.add_flag("--quiet", quiet, "no progress on stderr");
  if (const int rc = parse_or_exit(app, argc, argv, "fuzzypid tune"); rc >= 0) return rc;

  const cf::Family family = *cf::parse_enum(cf::kFamilyNames, family_name);
  tune::Options opt;
  opt.family = family;
  opt.budget = budget;
  opt.seed = seed;
  opt.threads = threads;
  opt.population = population;
  opt.objective = objective;
  opt.base = cf::paper_pid();
  opt.base.description.clear();
  if (!base_file.empty()) {
    cf::Error err;
    if (!cf::load(base_file, opt.base, err)) {
      std::fprintf(stderr, "fuzzypid tune: %s\n", err.to_string().c_str());
      return 1;
    }
    opt.base.tuning.reset();
  }
  opt.box = tune::default_box(family);
  for (const std::string& text : boxes) {
    cf::SearchBox b;
    if (!parse_box(text, b)) {
      std::fprintf(stderr, "fuzzypid tune: --box %s: expected NAME=MIN:MAX (log10, MIN <= MAX)\n",
                   text.c_str());
      return 2;
    }
    bool found = false;
    for (auto& d : opt.box) {
      if (d.name == b.name) {
        d = b;
        found = true;
      }
    }
    if (!found) {
      std::fprintf(stderr, "fuzzypid tune: --box: the %s family has no parameter '%s'\n",
                   cf::to_string(family), b.name.c_str());
      return 2;
    }
  }

  sim::ConditionFile file;
  cf::Error err;
  if (!sim::load_conditions(conditions, file, err)) {
    std::fprintf(stderr, "fuzzypid tune: %s\n", err.to_string().c_str());
    return 1;
  }
  const sim::ConditionSet* training = file.find(set);
  if (training == nullptr) {
    std::fprintf(stderr, "fuzzypid tune: %s has no set '%s' (it has: %s)\n", conditions.c_str(),
                 set.c_str(), file.set_names().c_str());
    return 1;
  }
  const std::string urdf = robot::default_urdf_path();
  robot::LoadResult loaded = robot::RobotModel::load(urdf);
  if (!loaded.model) {
    std::fprintf(stderr, "fuzzypid tune: cannot load %s: %s\n", urdf.c_str(), loaded.error.c_str());
    return 1;
  }
  sim::ExperimentOptions eo;
  eo.tick_s = opt.base.units.tick_s;
  std::string error;
  const auto experiment =
      sim::Experiment::create(*loaded.model, robot::paper_path_spec(), eo, error);
  if (!experiment) {
    std::fprintf(stderr, "fuzzypid tune: %s\n", error.c_str());
    return 1;
  }

  if (!quiet) {
    std::fprintf(stderr,
                 "fuzzypid tune: family %s, %zu training conditions (set %s), budget %" PRIu64
                 ", seed %" PRIu64 ", %u threads\n",
                 cf::to_string(family), training->conditions.size(), set.c_str(), budget, seed,
                 threads);
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
  auto result = tune::tune(*experiment, training->conditions, opt, error);
  if (!result) {
    std::fprintf(stderr, "fuzzypid tune: %s\n", error.c_str());
    return 2;
  }
  result->controller.tuning->conditions = conditions;
  result->controller.tuning->set = set;
  result->controller.description =
      "tuned " + std::string(cf::to_string(family)) + " on " + conditions + " [" + set + "]";
  if (const std::string bad = cf::save(out, result->controller); !bad.empty()) {
    std::fprintf(stderr, "fuzzypid tune: %s\n", bad.c_str());
    return 1;
  }
  const double rate = static_cast<double>(result->evaluations) / result->wall_s;
  std::printf("family %s: %" PRIu64 " evaluations (budget %" PRIu64
              ") in %.1f s, %.1f "
              "evaluations/s (%.0f condition runs/s), training cost %.6g (ITAE %.6g, overshoot "
              "penalty %.6g, %zu faulted runs) -> %s\n",
              cf::to_string(family), result->evaluations, budget, result->wall_s, rate,
              rate * static_cast<double>(training->conditions.size()), result->cost.total,
              result->cost.itae, result->cost.overshoot_penalty, result->cost.faulted_runs,
              out.c_str());
  return 0;
}

int run_export_header(int argc, char** argv) {
  CLI::App app{
      "fuzzypid export-header: write a controller file as a self-contained C++ header of "
      "constexpr configuration (no parser needed on the target).",
      "fuzzypid export-header"};
  std::string in, out, ns = "fuzzypid_controller";
  app.add_option("file", in, "controller file (TOML)")->required();
  app.add_option("--out", out, "header to write (default: stdout)");
  app.add_option("--namespace", ns, "namespace of the generated constants")
      ->check([](const std::string& s) -> std::string {
        if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_'))
          return "not a C++ identifier: " + s;
        for (char c : s)
          if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_')
            return "not a C++ identifier: " + s;
        return {};
      });
  if (const int rc = parse_or_exit(app, argc, argv, "fuzzypid export-header"); rc >= 0) return rc;
  cf::ControllerSpec spec;
  cf::Error err;
  if (!cf::load(in, spec, err)) {
    std::fprintf(stderr, "fuzzypid export-header: %s\n", err.to_string().c_str());
    return 1;
  }
  const std::string text = cf::export_header(spec, ns, in);
  if (out.empty()) {
    std::fputs(text.c_str(), stdout);
    return std::ferror(stdout) ? 1 : 0;
  }
  std::FILE* f = std::fopen(out.c_str(), "w");
  if (f == nullptr || std::fputs(text.c_str(), f) < 0 || std::fclose(f) != 0) {
    std::fprintf(stderr, "fuzzypid export-header: cannot write %s\n", out.c_str());
    return 1;
  }
  return 0;
}

}  // namespace fuzzypid::cli
