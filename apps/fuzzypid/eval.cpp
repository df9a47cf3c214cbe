// `fuzzypid eval`: the paper's supervisor from the shell. Rows e,ec on stdin ->
// e,ec,dKp,dKi,dKd on stdout.
#include <cstdio>
#include <cstring>
#include <iostream>

#include "commands.hpp"
#include "csv.hpp"
#include "fuzzypid/paper.hpp"

namespace fuzzypid::cli {

int run_eval(int argc, char** argv) {
  fuzzy::Conjunction conjunction = fuzzy::Conjunction::Minimum;
  paper::Tables tables = paper::Tables::Printed;
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
    } else if (std::strcmp(argv[k], "--corrected") == 0) {
      tables = paper::Tables::Corrected;
    } else if (std::strcmp(argv[k], "--help") == 0) {
      std::puts(
          "usage: fuzzypid eval [--and min|prod] [--corrected]\n"
          "Reads rows e,ec (fuzzy universe units) from stdin and writes e,ec,dKp,dKi,dKd using\n"
          "the paper's rule base (Tables 2-4; --corrected fixes the two suspected misprints).");
      return 0;
    } else {
      std::fprintf(stderr, "fuzzypid eval: unknown or incomplete option '%s'\n", argv[k]);
      return 2;
    }
  }

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
