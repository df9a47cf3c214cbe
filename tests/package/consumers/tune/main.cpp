// Uses the installed tune part: its optimiser (pagmo2) minimises a bowl with a known minimum at
// log10 x = (0.5, -1) within a small budget.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <fuzzypid/tune/tune.hpp>

int main() {
  namespace tune = fuzzypid::tune;
  const std::vector<tune::SearchBox> box{{"a", -2.0, 2.0}, {"b", -3.0, 1.0}};
  tune::MinimizeOptions options;
  options.budget = 2000;
  options.seed = 3;
  std::string error;
  const auto best = tune::minimize(
      [](const std::vector<double>& x) {
        return (x[0] - 0.5) * (x[0] - 0.5) + (x[1] + 1.0) * (x[1] + 1.0);
      },
      box, options, error);
  if (!best) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  std::printf("minimum %.3g at (%.4f, %.4f) after %llu evaluations\n", best->f, best->x[0],
              best->x[1], static_cast<unsigned long long>(best->evaluations));
  return best->evaluations <= options.budget && std::fabs(best->x[0] - 0.5) < 1e-2 &&
                 std::fabs(best->x[1] + 1.0) < 1e-2
             ? 0
             : 1;
}
