// A static check of a loaded rule base (`fuzzypid check-rules FILE`): where no rule fires, which
// rules repeat or contradict each other, and whether each output is monotone in each input.
//
// Coverage and monotonicity are sampled: the inputs' ranges are scanned on a regular grid of
// `points_per_input` points per axis (both ends included; fewer when the whole grid would exceed
// `max_points`). A grid point is a gap for an output when no rule concluding on that output has a
// firing strength > 0 there (the output then takes its default, or its previous value with
// lock-previous). Gap points are grouped into boxes of grid neighbours (connected along the axes);
// a gap narrower than the grid spacing can be missed. Monotonicity compares neighbouring grid
// points along each input, the other inputs fixed, wherever the output fired at both.
//
// Repeats and contradictions are found from the rules' text: two rules whose antecedents are the
// same (the same propositions joined by the same connective, in any order) and that conclude on a
// common output either repeat each other (same term and hedges on every common output) or
// contradict each other (another term on some common output).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "fuzzypid/rulefile/rule_file.hpp"

namespace fuzzypid::rulefile {

struct RuleCheckOptions {
  std::size_t points_per_input = 101;  // >= 2
  std::size_t max_points = 250000;     // whole grid
};

// A box of the input space, made of grid points where some output has no rule firing.
struct CoverageGap {
  std::vector<double> min, max;      // per input: the box's extreme grid coordinates
  std::vector<double> example;       // one grid point of the box
  std::size_t points = 0;            // grid points in the box
  std::vector<std::size_t> outputs;  // outputs without a firing rule somewhere in the box
};

struct RulePair {
  std::size_t first = 0, second = 0;  // rule indices in file order, first < second
  bool contradiction = false;         // else a repeat
  std::size_t output = 0;             // contradiction: the output concluded differently
};

enum class Monotonicity { Constant, Increasing, Decreasing, NotMonotone, NeverFires };

struct MonotonicityFinding {
  std::size_t output = 0, input = 0;
  Monotonicity kind = Monotonicity::Constant;
  // NotMonotone: a point where the output rises along the input, and one where it falls.
  std::vector<double> rise_at, fall_at;
};

struct RuleCheckReport {
  std::size_t points_per_input = 0;
  std::size_t grid_points = 0;
  std::vector<CoverageGap> gaps;
  std::vector<RulePair> pairs;
  std::vector<MonotonicityFinding> monotonicity;  // output-major, every (output, input)
};

// The model must be valid (loaded by this library). Allocates; evaluation itself does not.
RuleCheckReport check_rules(const Model& model, const RuleCheckOptions& options = {});

// The report as text for people: one finding a line, names as the file writes them, rules as
// "rule N" (1-based, file order) with their text.
std::string to_text(const Model& model, const RuleCheckReport& report);

const char* to_string(Monotonicity m) noexcept;

}  // namespace fuzzypid::rulefile
