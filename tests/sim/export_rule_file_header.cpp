// Writes the header `fuzzypid export-header` would write for a controller file, through the same
// library calls (fuzzypid::codegen::check_float_range, export_header), for controller files with a
// rule file, which the command line does not pass on yet.
//
// usage: export_rule_file_header CONTROLLER.toml NAMESPACE OUT.hpp
#include <cstdio>
#include <fstream>
#include <string>

#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid/codegen/export_header.hpp"

int main(int argc, char** argv) {
  namespace cf = fuzzypid::controller_file;
  namespace ctl = fuzzypid::controller;
  if (argc != 4) {
    std::fprintf(stderr, "usage: export_rule_file_header CONTROLLER.toml NAMESPACE OUT.hpp\n");
    return 2;
  }
  ctl::ControllerSpec spec;
  fuzzypid::FileError err;
  if (!cf::load(argv[1], spec, err)) {
    std::fprintf(stderr, "%s\n", err.to_string().c_str());
    return 1;
  }
  if (spec.supervisor.rule_model == nullptr) {
    std::fprintf(stderr, "%s: no rule file\n", argv[1]);
    return 1;
  }
  if (const std::string bad = fuzzypid::codegen::check_float_range(spec); !bad.empty()) {
    std::fprintf(stderr, "%s: %s\n", argv[1], bad.c_str());
    return 1;
  }
  std::ofstream out(argv[3], std::ios::binary);
  out << fuzzypid::codegen::export_header(spec, argv[2], argv[1]);
  return out.good() ? 0 : 1;
}
