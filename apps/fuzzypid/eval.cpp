// `fuzzypid eval`: the paper's supervisor from the shell. Rows e,ec on stdin ->
// e,ec,dKp,dKi,dKd on stdout. With --fis FILE or --fll FILE, the loaded rule base instead: rows of
// its inputs (in file order) -> the inputs followed by its outputs.
#include <cstdio>
#include <cstring>
#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "csv.hpp"
#include "fuzzypid/fuzzy/engine.hpp"
#include "fuzzypid/rulefile/rule_file.hpp"
#include "fuzzypid/paper.hpp"

namespace fuzzypid::cli {

namespace {

// Evaluates a rule file on every row of stdin; 0, 1 (bad file or row) like the paper path.
int eval_rule_file(const std::string& path, bool fis) {
  auto model = std::make_unique<rulefile::Model>();
  rulefile::LoadError error;
  const bool loaded = fis ? rulefile::load_fis(path, *model, error) : rulefile::load_fll(path, *model, error);
  if (!loaded) {
    std::fprintf(stderr, "fuzzypid eval: %s\n", error.to_string().c_str());
    return 1;
  }
  auto engine = std::make_unique<fuzzy::Engine<double>>(*model);
  const std::size_t n_in = model->num_inputs;
  const std::size_t n_out = model->num_outputs;
  std::string header;
  for (std::size_t i = 0; i < n_in; ++i)
    header += (i ? "," : "") + std::string(model->inputs[i].name.data());
  for (std::size_t o = 0; o < n_out; ++o)
    header += "," + std::string(model->outputs[o].name.data());
  std::puts(header.c_str());
  CsvReader reader(std::cin);
  reader.expect_columns(n_in, n_in);
  CsvRow row;
  double values[fuzzy::kMaxInputs + fuzzy::kMaxOutputs] = {};
  while (reader.next(row)) {
    for (std::size_t i = 0; i < n_in; ++i)
      values[i] = row.values[i];
    (void)engine->evaluate(values, values + n_in);
    write_row(stdout, values, n_in + n_out);
  }
  if (!reader.error().empty()) {
    std::fprintf(stderr, "fuzzypid eval: %s\n", reader.error().c_str());
    return 1;
  }
  return 0;
}

}  // namespace

int run_eval(int argc, char** argv) {
  fuzzy::Conjunction conjunction = fuzzy::Conjunction::Minimum;
  paper::Tables tables = paper::Tables::Printed;
  std::string rule_file;
  bool rule_file_is_fis = false;
  for (int k = 0; k < argc; ++k) {
    if (std::strcmp(argv[k], "--and") == 0 && k + 1 < argc) {
      const char* v = argv[++k];
      if (std::strcmp(v, "min") == 0) {
        conjunction = fuzzy::Conjunction::Minimum;
      } else if (std::strcmp(v, "prod") == 0) {
        conjunction = fuzzy::Conjunction::Product;
      } else {
        std::fprintf(stderr, "fuzzypid eval: --and takes min or prod, not '%s'\n", v);
        return 2;
      }
    } else if ((std::strcmp(argv[k], "--fis") == 0 || std::strcmp(argv[k], "--fll") == 0) &&
               k + 1 < argc) {
      rule_file_is_fis = std::strcmp(argv[k], "--fis") == 0;
      rule_file = argv[++k];
    } else if (std::strcmp(argv[k], "--corrected") == 0) {
      tables = paper::Tables::Corrected;
    } else if (std::strcmp(argv[k], "--help") == 0) {
      std::puts(
          "usage: fuzzypid eval [--and min|prod] [--corrected]\n"
          "       fuzzypid eval --fis FILE | --fll FILE\n"
          "Reads rows e,ec (fuzzy universe units) from stdin and writes e,ec,dKp,dKi,dKd using\n"
          "the paper's rule base (Tables 2-4; --corrected fixes the two suspected misprints).\n"
          "With a MATLAB .fis or fuzzylite .fll file, reads rows of that system's inputs (file\n"
          "order) and writes the inputs followed by its outputs (docs/rule_files.md).");
      return 0;
    } else {
      std::fprintf(stderr, "fuzzypid eval: unknown or incomplete option '%s'\n", argv[k]);
      return 2;
    }
  }

  if (!rule_file.empty()) return eval_rule_file(rule_file, rule_file_is_fis);

  const auto system = paper::make_system<double>(conjunction, tables);
  CsvReader reader(std::cin);
  reader.expect_columns(2, 2);
  CsvRow row;
  std::puts("e,ec,dKp,dKi,dKd");
  while (reader.next(row)) {
    const auto r = system.infer(row.values[0], row.values[1]);
    const double out[5] = {row.values[0], row.values[1], r.output[0], r.output[1], r.output[2]};
    write_row(stdout, out, 5);
  }
  if (!reader.error().empty()) {
    std::fprintf(stderr, "fuzzypid eval: %s\n", reader.error().c_str());
    return 1;
  }
  return 0;
}

}  // namespace fuzzypid::cli
