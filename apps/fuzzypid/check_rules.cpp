// `fuzzypid check-rules FILE`: the rule-base check of rulefile/rule_check.hpp on a .fis, .fll or
// .fcl file (by extension): regions where no rule fires, repeated and contradictory rules, and
// the monotonicity of each output in each input. The report goes to stdout. Exit 0 when a rule
// fires everywhere on the grid (or with --allow-gaps), 1 on a coverage gap or a file that does
// not load, 2 on bad usage.
#include <cstdio>
#include <memory>
#include <string>

#include "cli.hpp"
#include "commands.hpp"
#include "fuzzypid/rulefile/rule_check.hpp"
#include "fuzzypid/rulefile/rule_file.hpp"

namespace fuzzypid::cli {

namespace {

constexpr const char* kTool = "fuzzypid check-rules";

struct CheckRulesOptions {
  std::string file;
  bool allow_gaps = false;
  std::size_t grid = 101;
};

int run_check_rules(const CheckRulesOptions& o) {
  auto model = std::make_unique<rulefile::Model>();
  rulefile::LoadError error;
  if (!rulefile::load_rule_file(o.file, *model, error)) {
    std::fprintf(stderr, "%s: %s\n", kTool, error.to_string().c_str());
    return kExitFailure;
  }
  rulefile::RuleCheckOptions options;
  options.points_per_input = o.grid;
  const rulefile::RuleCheckReport report = rulefile::check_rules(*model, options);
  std::fputs(rulefile::to_text(*model, report).c_str(), stdout);
  if (report.gaps.empty()) return kExitOk;
  std::fprintf(stderr, "%s: %s: %zu region(s) where no rule fires for some output%s\n", kTool,
               o.file.c_str(), report.gaps.size(),
               o.allow_gaps ? " (allowed by --allow-gaps)" : "; --allow-gaps accepts them");
  return o.allow_gaps ? kExitOk : kExitFailure;
}

}  // namespace

void add_check_rules_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<CheckRulesOptions>();
  CLI::App* cmd = app.add_subcommand(
      "check-rules",
      "Checks a rule base (.fis, .fll or .fcl, by extension): regions of the input ranges where "
      "no rule fires (grid scan), rules that repeat or contradict each other, and whether each "
      "output is monotone in each input. Exits 1 on a coverage gap unless --allow-gaps.");
  cmd->add_option("FILE", options->file, "the rule base")->required();
  cmd->add_flag("--allow-gaps", options->allow_gaps, "exit 0 even where no rule fires");
  cmd->add_option("--grid", options->grid, "grid points per input (fewer beyond 250,000 in all)")
      ->check(CLI::Range(std::size_t{2}, std::size_t{100000}))
      ->option_text("N");
  cmd->callback([&run, options] { run = [options] { return run_check_rules(*options); }; });
}

}  // namespace fuzzypid::cli
