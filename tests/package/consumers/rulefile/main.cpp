// Uses the installed rulefile part: loads the installed paper rule base (argv[1]) and evaluates it.
#include <cmath>
#include <cstdio>
#include <memory>

#include <fuzzypid/fuzzy/engine.hpp>
#include <fuzzypid/rulefile/rule_file.hpp>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  auto model = std::make_unique<fuzzypid::rulefile::Model>();
  fuzzypid::rulefile::LoadError error;
  if (!fuzzypid::rulefile::load_rule_file(argv[1], *model, error)) {
    std::fprintf(stderr, "%s\n", error.to_string().c_str());
    return 1;
  }
  return model->num_inputs == 2 ? 0 : 1;
}
