// `fuzzypid eval`: the paper's supervisor from the shell. Rows e,ec on stdin ->
// e,ec,dKp,dKi,dKd on stdout. With --fis, --fll or --fcl FILE, the loaded rule base instead: rows
// of its inputs (in file order) -> the inputs followed by its outputs.
//
// A row on which no rule fires (Status::NoRuleFired) is still written -- with the rule base's
// default outputs (0 when the default is NaN), so that output rows keep matching input rows -- but
// each such row is reported on stderr with its line and the run exits 1: a number that no rule
// produced is never passed off as an inference.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "cli.hpp"
#include "commands.hpp"
#include "csv.hpp"
#include "fuzzypid/fuzzy/engine.hpp"
#include "fuzzypid/fuzzy/operators.hpp"
#include "fuzzypid/paper.hpp"
#include "fuzzypid/rulefile/rule_file.hpp"
#include "fuzzypid/status.hpp"

namespace fuzzypid::cli {

namespace {

constexpr const char* kTool = "fuzzypid eval";
// Rows with no rule fired are each named on stderr up to this count, then only counted.
constexpr std::size_t kMaxNamedRows = 10;

// The conjunctions the paper's table system takes, named by the enum's own to_string.
const std::array<EnumName<fuzzy::Conjunction>, 2> kAndNames = {
    {{fuzzy::Conjunction::Minimum, to_string(fuzzy::Conjunction::Minimum)},
     {fuzzy::Conjunction::Product, to_string(fuzzy::Conjunction::Product)}}};

struct EvalOptions {
  fuzzy::Conjunction conjunction = fuzzy::Conjunction::Minimum;
  bool corrected = false;
  std::string fis, fll, fcl;
};

// Counts the rows whose evaluation reported NoRuleFired and names the first few.
class NoRuleReport {
 public:
  void row(std::size_t line) {
    if (++count_ <= kMaxNamedRows)
      std::fprintf(stderr, "%s: line %zu: no rule fired; the row holds the default outputs\n",
                   kTool, line);
  }
  // The exit code of a run whose input was read completely.
  int finish() const {
    if (count_ == 0) return kExitOk;
    std::fprintf(stderr, "%s: no rule fired on %zu row(s); their outputs are not inferences\n",
                 kTool, count_);
    return kExitFailure;
  }

 private:
  std::size_t count_ = 0;
};

int input_failure(const CsvReader& reader) {
  std::string error = reader.error();
  if (error.empty()) error = stdin_read_error();
  if (error.empty()) return kExitOk;
  std::fprintf(stderr, "%s: %s\n", kTool, error.c_str());
  return kExitFailure;
}

// Evaluates a rule file on every row of stdin.
int eval_rule_file(const EvalOptions& o) {
  auto model = std::make_unique<rulefile::Model>();
  rulefile::LoadError error;
  bool loaded = false;
  if (!o.fis.empty()) {
    loaded = rulefile::load_fis(o.fis, *model, error);
  } else if (!o.fll.empty()) {
    loaded = rulefile::load_fll(o.fll, *model, error);
  } else {
    loaded = rulefile::load_fcl(o.fcl, *model, error);
  }
  if (!loaded) {
    std::fprintf(stderr, "%s: %s\n", kTool, error.to_string().c_str());
    return kExitFailure;
  }
  auto engine = std::make_unique<fuzzy::Engine<double>>(*model);
  const std::size_t n_in = model->num_inputs;
  const std::size_t n_out = model->num_outputs;
  std::string header;
  for (std::size_t i = 0; i < n_in; ++i)
    header += (i ? "," : "") + std::string(model->inputs[i].name.data());
  for (std::size_t o_index = 0; o_index < n_out; ++o_index)
    header += "," + std::string(model->outputs[o_index].name.data());
  std::puts(header.c_str());
  CsvReader reader(std::cin);
  reader.expect_columns(n_in, n_in);
  CsvRow row;
  NoRuleReport no_rule;
  double values[fuzzy::kMaxInputs + fuzzy::kMaxOutputs] = {};
  while (reader.next(row)) {
    for (std::size_t i = 0; i < n_in; ++i)
      values[i] = row.values[i];
    const Status status = engine->evaluate(values, values + n_in);
    if (is_fault(status)) {
      std::fprintf(stderr, "%s: line %zu: evaluation failed: %s\n", kTool, row.line,
                   to_string(status));
      return kExitFailure;
    }
    write_row(stdout, values, n_in + n_out);
    if (status == Status::NoRuleFired) no_rule.row(row.line);
  }
  if (const int rc = input_failure(reader); rc != kExitOk) return rc;
  return no_rule.finish();
}

int eval_paper(const EvalOptions& o) {
  const auto system = paper::make_system<double>(
      o.conjunction, o.corrected ? paper::Tables::Corrected : paper::Tables::Printed);
  CsvReader reader(std::cin);
  reader.expect_columns(2, 2);
  CsvRow row;
  NoRuleReport no_rule;
  std::puts("e,ec,dKp,dKi,dKd");
  while (reader.next(row)) {
    const auto r = system.infer(row.values[0], row.values[1]);
    if (is_fault(r.status)) {
      std::fprintf(stderr, "%s: line %zu: inference failed: %s\n", kTool, row.line,
                   to_string(r.status));
      return kExitFailure;
    }
    const double out[5] = {row.values[0], row.values[1], r.output[0], r.output[1], r.output[2]};
    write_row(stdout, out, 5);
    if (r.status == Status::NoRuleFired) no_rule.row(row.line);
  }
  if (const int rc = input_failure(reader); rc != kExitOk) return rc;
  return no_rule.finish();
}

int run_eval(const EvalOptions& o) {
  if (const std::string error = check_stdin_is_data(); !error.empty()) {
    std::fprintf(stderr, "%s: %s\n", kTool, error.c_str());
    return kExitFailure;
  }
  if (!o.fis.empty() || !o.fll.empty() || !o.fcl.empty()) return eval_rule_file(o);
  return eval_paper(o);
}

}  // namespace

void add_eval_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<EvalOptions>();
  CLI::App* cmd = app.add_subcommand(
      "eval",
      "Rows e,ec (fuzzy universe units) -> e,ec,dKp,dKi,dKd from the paper's rule base (Tables "
      "2-4). With --fis, --fll or --fcl, rows of that rule base's inputs (file order) -> the "
      "inputs followed by its outputs (docs/rule_files.md). A row on which no rule fires is "
      "reported on stderr and the run exits 1.");
  CLI::Option* conj = add_enum_option(*cmd, "--and", options->conjunction, kAndNames,
                                      "fuzzy AND of the paper's system");
  CLI::Option* corrected = cmd->add_flag(
      "--corrected", options->corrected,
      "the paper's tables with the two suspected misprints fixed (docs/reproduction.md)");
  CLI::Option* fis =
      cmd->add_option("--fis", options->fis, "a MATLAB .fis rule base")->option_text("FILE");
  CLI::Option* fll =
      cmd->add_option("--fll", options->fll, "a fuzzylite .fll rule base")->option_text("FILE");
  CLI::Option* fcl =
      cmd->add_option("--fcl", options->fcl, "an IEC 61131-7 .fcl rule base")->option_text("FILE");
  fis->excludes(fll)->excludes(fcl)->excludes(conj)->excludes(corrected);
  fll->excludes(fcl)->excludes(conj)->excludes(corrected);
  fcl->excludes(conj)->excludes(corrected);
  cmd->callback([&run, options] { run = [options] { return run_eval(*options); }; });
}

}  // namespace fuzzypid::cli
