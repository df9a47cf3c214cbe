// `fuzzypid pick DIR --rule RULE`: one controller of a front (fuzzypid tune --front-out DIR) chosen
// by a stated rule; `fuzzypid hypervolume DIR...`: each front's hypervolume against one common
// reference point (tune/pick.hpp, docs/tuning.md "Picking a point").
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli.hpp"
#include "commands.hpp"
#include "fuzzypid/tune/pick.hpp"

namespace fuzzypid::cli {

namespace {

struct PickOptions {
  std::string dir, rule = "knee", on = "training";
};

// The columns of `t` that `on` names; null with a message when the front has none.
const std::vector<std::vector<double>>* columns(const tune::FrontTable& t, const std::string& on,
                                                const std::string& dir, const char* tool) {
  if (on == "training") return &t.training;
  if (!t.validation.empty()) return &t.validation;
  std::fprintf(stderr,
               "%s: %s/front.csv has no validation columns (tune with --validation or "
               "--report-set)\n",
               tool, dir.c_str());
  return nullptr;
}

int run_pick(const PickOptions& o) {
  constexpr const char* kTool = "fuzzypid pick";
  std::string error;
  const auto rule = tune::parse_pick_rule(o.rule, error);
  if (!rule) {
    std::fprintf(stderr, "%s: --rule %s\n", kTool, error.c_str());
    return kExitUsage;
  }
  const auto table = tune::read_front(o.dir, error);
  if (!table) {
    std::fprintf(stderr, "%s: %s\n", kTool, error.c_str());
    return kExitFailure;
  }
  const auto* points = columns(*table, o.on, o.dir, kTool);
  if (points == nullptr) return kExitFailure;
  const auto chosen = tune::pick(table->objectives, *points, *rule, error);
  if (!chosen) {
    std::fprintf(stderr, "%s: %s: %s\n", kTool, o.dir.c_str(), error.c_str());
    return kExitFailure;
  }
  std::printf("%s\n", (std::filesystem::path(o.dir) / table->files[*chosen]).string().c_str());
  std::fprintf(stderr, "%s: point %zu by %s on %s:", kTool, *chosen, o.rule.c_str(), o.on.c_str());
  for (std::size_t i = 0; i < table->objectives.size(); ++i)
    std::fprintf(stderr, " %s %.6g", table->objectives[i].c_str(), (*points)[*chosen][i]);
  std::fprintf(stderr, "\n");
  return kExitOk;
}

struct HypervolumeOptions {
  std::vector<std::string> dirs;
  std::string on = "training";
  std::optional<double> drop_at;  // --drop-at X
};

int run_hypervolume(const HypervolumeOptions& o) {
  constexpr const char* kTool = "fuzzypid hypervolume";
  std::vector<std::vector<std::vector<double>>> fronts;
  std::vector<std::size_t> dropped;
  std::vector<std::string> objectives;
  for (const std::string& dir : o.dirs) {
    std::string error;
    const auto table = tune::read_front(dir, error);
    if (!table) {
      std::fprintf(stderr, "%s: %s\n", kTool, error.c_str());
      return kExitFailure;
    }
    if (!objectives.empty() && table->objectives != objectives) {
      std::fprintf(stderr, "%s: %s has other objectives than %s: fronts compare on the same ones\n",
                   kTool, dir.c_str(), o.dirs.front().c_str());
      return kExitFailure;
    }
    objectives = table->objectives;
    const auto* points = columns(*table, o.on, dir, kTool);
    if (points == nullptr) return kExitFailure;
    std::vector<std::vector<double>> kept;
    for (const auto& p : *points)
      if (!o.drop_at || *std::max_element(p.begin(), p.end()) < *o.drop_at) kept.push_back(p);
    dropped.push_back(points->size() - kept.size());
    fronts.push_back(std::move(kept));
  }
  const std::vector<double> reference = tune::common_reference(fronts);
  if (reference.empty()) {
    std::fprintf(stderr, "%s: every point was dropped (--drop-at)\n", kTool);
    return kExitFailure;
  }
  std::printf("# reference (%s):", o.on.c_str());
  for (std::size_t i = 0; i < objectives.size(); ++i)
    std::printf(" %s %.17g", objectives[i].c_str(), reference[i]);
  std::printf("\nfront,points,dropped,hypervolume\n");
  for (std::size_t k = 0; k < fronts.size(); ++k)
    std::printf("%s,%zu,%zu,%.17g\n", o.dirs[k].c_str(), fronts[k].size(), dropped[k],
                tune::hypervolume(fronts[k], reference));
  return kExitOk;
}

}  // namespace

void add_pick_command(CLI::App& app, std::function<int()>& run) {
  auto o = std::make_shared<PickOptions>();
  CLI::App* cmd = app.add_subcommand(
      "pick",
      "Choose one controller of a front (fuzzypid tune --front-out DIR) by a stated rule and "
      "print its file; its objectives go to stderr.");
  cmd->add_option("DIR", o->dir, "the front's folder (front.csv)")->required();
  cmd->add_option("--rule", o->rule,
                  "knee (nearest the ideal point, each objective scaled to [0, 1] over the "
                  "front), min:OBJ (the smallest OBJ) or max:OBJ=X (within OBJ <= X, the smallest "
                  "first other objective) (default knee)");
  cmd->add_option("--on", o->on,
                  "the columns to judge on: training or validation (default training)")
      ->check(CLI::IsMember({"training", "validation"}));
  cmd->callback([&run, o] { run = [o] { return run_pick(*o); }; });
}

void add_hypervolume_command(CLI::App& app, std::function<int()>& run) {
  auto o = std::make_shared<HypervolumeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "hypervolume",
      "The hypervolume of each front (fuzzypid tune --front-out DIR) against one reference point: "
      "per objective the largest value over all the fronts plus 10 % of its range (1 when the "
      "range is 0). Larger is better. CSV on stdout, the reference on a # line.");
  cmd->add_option("DIR", o->dirs, "the fronts' folders, all over the same objectives")->required();
  cmd->add_option("--drop-at", o->drop_at,
                  "leave out (and count as dropped) the points with an objective at or above X: "
                  "with X the fault cost, those with a faulted run, which would otherwise set the "
                  "reference point")
      ->check(CLI::Number)
      ->option_text("X");
  cmd->add_option("--on", o->on,
                  "the columns to judge on: training or validation (default training)")
      ->check(CLI::IsMember({"training", "validation"}));
  cmd->callback([&run, o] { run = [o] { return run_hypervolume(*o); }; });
}

}  // namespace fuzzypid::cli
