// `fuzzypid export-rules`: a fuzzy-rules controller's supervisor (supervisor::RuleTable) as a
// .fll/.fcl/.fis rule file, the `fuzzy` controller file that runs it, and its gain-ratio surfaces
// as CSV (docs/tuning.md, "Exporting a tuned rule base").
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "commands.hpp"
#include "fuzzypid/controller/joint_controllers.hpp"
#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid/rulefile/rule_file.hpp"
#include "fuzzypid/rulefile/rule_table_export.hpp"
#include "output_files.hpp"

namespace fuzzypid::cli {

namespace {

namespace cf = controller_file;
namespace fs = std::filesystem;

constexpr const char* kTool = "fuzzypid export-rules";

struct ExportRulesOptions {
  std::string in, out, format, controller_out, surface;
  unsigned surface_points = 41;
  bool out_given = false, controller_out_given = false, surface_given = false;
  GivenOptions given;
};

// The format named by a path's extension (any case), or "".
std::string format_of(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".fll" || ext == ".fcl" || ext == ".fis") return ext.substr(1);
  return {};
}

// The path's folder with symbolic links resolved, joined with its file name: two spellings of the
// same output compare equal, and a relative path between two outputs is the one a reader follows.
fs::path resolved(const std::string& path) {
  std::error_code ec;
  const fs::path p(path);
  const fs::path folder = p.has_parent_path() ? p.parent_path() : fs::path(".");
  fs::path dir = fs::weakly_canonical(fs::absolute(folder, ec), ec);
  if (ec) dir = folder.lexically_normal();  // unreachable after check_output_path
  return dir / p.filename();
}

int usage(const std::string& message) {
  std::fprintf(stderr, "%s: %s\n", kTool, message.c_str());
  return kExitUsage;
}

// The grid of the surfaces: x = Ke e and y = Kec ec over +-1.2 c_max (beyond c_max the shoulders
// hold the outer rules), written in e and ec; ratios K/K0 before the gain bounds clamp them.
std::string surface_csv(const supervisor::RuleTable<double>& table,
                        const controller::ControllerSpec& spec, unsigned n) {
  const double x_max = 1.2 * table.e_centers.back();
  const double y_max = 1.2 * table.ec_centers.back();
  std::string text = "e_rad,ec_rad_s,kp_ratio,ki_ratio,kd_ratio\n";
  char buf[160];
  // Node k at c (2k - (n - 1)) / (n - 1): symmetric about 0, and 0 itself when n is odd.
  const auto at = [n](double c, unsigned k) { return c * (2.0 * k - (n - 1.0)) / (n - 1.0); };
  for (unsigned a = 0; a < n; ++a) {
    const double x = at(x_max, a);
    for (unsigned b = 0; b < n; ++b) {
      const double y = at(y_max, b);
      std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.17g,%.17g,%.17g\n",
                    x / spec.supervisor.error_scale, y / spec.supervisor.error_rate_scale,
                    table.ratio(x, y, 0), table.ratio(x, y, 1), table.ratio(x, y, 2));
      text += buf;
    }
  }
  return text;
}

int run_export_rules(const ExportRulesOptions& o) {
  // Usage first, before reading anything: what to write, in which format, and where.
  if (o.controller_out_given && !o.out_given)
    return usage("--controller-out: needs --out, the rule file the controller names");
  if (!o.out_given && !o.surface_given)
    return usage("nothing to write: give --out (a rule file), --surface (a CSV) or both");
  if (const std::string bad = o.given.refuse_unused({"--surface-points"}, o.surface_given,
                                                    "--surface", "no --surface CSV is written");
      !bad.empty())
    return usage(bad);
  if (const std::string bad = o.given.refuse_unused({"--format"}, o.out_given, "--out",
                                                    "no rule file is written without --out");
      !bad.empty())
    return usage(bad);
  std::string format = o.format;
  if (o.out_given) {
    const std::string by_name = format_of(o.out);
    if (format.empty()) {
      if (by_name.empty())
        return usage("--format: not given, and --out '" + o.out +
                     "' does not end in .fll, .fcl or .fis");
      format = by_name;
    } else if (!by_name.empty() && by_name != format) {
      return usage("--out: '" + o.out + "' ends in ." + by_name + " but --format is " + format);
    } else if (by_name.empty() && o.controller_out_given) {
      return usage("--out: '" + o.out + "' must end in ." + format +
                   " for --controller-out: the controller file's reader picks the format by "
                   "the rule file's extension");
    }
  }
  struct Output {
    const char* option;
    const std::string* path;
    bool given;
  };
  const Output outputs[] = {{"--out", &o.out, o.out_given},
                            {"--controller-out", &o.controller_out, o.controller_out_given},
                            {"--surface", &o.surface, o.surface_given}};
  for (const Output& w : outputs) {
    if (!w.given) continue;
    if (const std::string bad = check_output_path(*w.path, {o.in}); !bad.empty())
      return usage(std::string(w.option) + ": " + bad);
  }
  for (std::size_t a = 0; a < 3; ++a)
    for (std::size_t b = a + 1; b < 3; ++b)
      if (outputs[a].given && outputs[b].given &&
          resolved(*outputs[a].path) == resolved(*outputs[b].path))
        return usage(std::string(outputs[b].option) + ": '" + *outputs[b].path +
                     "' is the same file as " + outputs[a].option);

  controller::ControllerSpec spec;
  FileError err;
  if (!cf::load(o.in, spec, err)) {
    std::fprintf(stderr, "%s: %s\n", kTool, err.to_string().c_str());
    return kExitFailure;
  }
  if (!controller::family_traits(spec.family).rule_table) {
    std::fprintf(stderr,
                 "%s: %s: a '%s' controller has no rule table; export-rules reads controllers "
                 "with one (fuzzy-rules)\n",
                 kTool, o.in.c_str(), controller::to_string(spec.family));
    return kExitFailure;
  }
  const supervisor::RuleTable<double> table = controller::rule_table(spec);

  std::string rules, controller_text;
  if (o.out_given) {
    std::string error;
    const bool ok = format == "fll"   ? rulefile::rule_table_to_fll(table, rules, error)
                    : format == "fcl" ? rulefile::rule_table_to_fcl(table, rules, error)
                                      : rulefile::rule_table_to_fis(table, rules, error);
    if (!ok) {
      std::fprintf(stderr, "%s: %s: %s\n", kTool, o.in.c_str(), error.c_str());
      return kExitFailure;
    }
  }
  if (o.controller_out_given) {
    // The rule file as the new controller will load it, so the controller is checked like one
    // read from disk before anything is written.
    auto model = std::make_shared<rulefile::Model>();
    rulefile::LoadError load_error;
    const bool parsed = format == "fll"   ? rulefile::parse_fll(rules, o.out, *model, load_error)
                        : format == "fcl" ? rulefile::parse_fcl(rules, o.out, *model, load_error)
                                          : rulefile::parse_fis(rules, o.out, *model, load_error);
    if (!parsed) {
      std::fprintf(stderr, "%s: the written rule file does not load: %s\n", kTool,
                   load_error.to_string().c_str());
      return kExitFailure;
    }
    const fs::path rel =
        resolved(o.out).lexically_relative(resolved(o.controller_out).parent_path());
    std::string description = "the fuzzy-rules controller " + o.in + " with its rule table as " +
                              rel.generic_string() + " (fuzzypid export-rules)";
    if (!spec.description.empty()) description += "; it was: " + spec.description;
    const controller::ControllerSpec fuzzy =
        controller::fuzzy_from_rule_table(spec, rel.generic_string(), model, description);
    if (const std::string bad = controller::validate(fuzzy); !bad.empty()) {
      std::fprintf(stderr, "%s: the fuzzy controller is not valid: %s\n", kTool, bad.c_str());
      return kExitFailure;
    }
    controller_text = cf::to_toml(fuzzy);
  }

  // The rule file before the controller that names it.
  if (o.out_given)
    if (const std::string bad = write_output_file(o.out, rules, "export-rules"); !bad.empty()) {
      std::fprintf(stderr, "%s: %s\n", kTool, bad.c_str());
      return kExitFailure;
    }
  if (o.controller_out_given)
    if (const std::string bad =
            write_output_file(o.controller_out, controller_text, "export-rules");
        !bad.empty()) {
      std::fprintf(stderr, "%s: %s\n", kTool, bad.c_str());
      return kExitFailure;
    }
  if (o.surface_given)
    if (const std::string bad = write_output_file(
            o.surface, surface_csv(table, spec, o.surface_points), "export-rules");
        !bad.empty()) {
      std::fprintf(stderr, "%s: %s\n", kTool, bad.c_str());
      return kExitFailure;
    }
  return kExitOk;
}

}  // namespace

void add_export_rules_command(CLI::App& app, std::function<int()>& run) {
  auto o = std::make_shared<ExportRulesOptions>();
  CLI::App* cmd = app.add_subcommand(
      "export-rules",
      "Write a fuzzy-rules controller's supervisor (schedule ramp times rule table) as a rule "
      "file that fuzzylite and the fuzzy family read, optionally the fuzzy controller file that "
      "runs it, and the gain-ratio surfaces K/K0 over (e, ec) as CSV.");
  cmd->add_option("file", o->in, "fuzzy-rules controller file (TOML)")->required();
  CLI::Option* out = cmd->add_option("--out", o->out, "rule file to write (.fll, .fcl or .fis)");
  cmd->add_option("--format", o->format,
                  "fll, fcl or fis (default: --out's extension); fis only for ratios R = 1")
      ->check(CLI::IsMember({"fll", "fcl", "fis"}));
  CLI::Option* controller_out =
      cmd->add_option("--controller-out", o->controller_out,
                      "fuzzy controller file to write, naming --out relative to its folder");
  CLI::Option* surface = cmd->add_option(
      "--surface", o->surface,
      "CSV to write: e_rad, ec_rad_s, kp_ratio, ki_ratio, kd_ratio on a grid over +-1.2 c_max "
      "of the supervisor's universe (scripts/plot_rule_surfaces.py plots it)");
  cmd->add_option("--surface-points", o->surface_points,
                  "grid points per axis of --surface (default 41)")
      ->check(unsigned_in(3, 1001));
  cmd->callback([&run, o, out, controller_out, surface, cmd] {
    o->given = GivenOptions(*cmd);
    o->out_given = out->count() > 0;
    o->controller_out_given = controller_out->count() > 0;
    o->surface_given = surface->count() > 0;
    run = [o] { return run_export_rules(*o); };
  });
}

}  // namespace fuzzypid::cli
