// A rule base as straight-line C++ for export-header: the supervisor's inference written out rule
// by rule, with the model's numbers as literals, so a microcontroller runs no interpreter loop
// over the model (private to fuzzypid::codegen).
#pragma once

#include <array>
#include <cstddef>
#include <string>

#include "fuzzypid/fuzzy/engine_model.hpp"

namespace fuzzypid::codegen {

// Where the supervisor's signals sit in the rule base: the model's index of e and ec, and of
// dKp, dKi and dKd.
struct SupervisorBinding {
  std::array<std::size_t, 2> input_of{};
  std::array<std::size_t, 3> output_of{};
};

// "" when `model` can be written as straight-line code, else what it uses that the generator does
// not cover (the caller then exports the interpreted engine). Covered: inputs of any term shape,
// rules of propositions joined by `and`/`or` with hedges (Octave's power hedges included), weights,
// General and Threshold activation, and Takagi-Sugeno outputs (weighted average or sum) of
// constant and linear terms, with lock-range, lock-previous and defaults. Not covered: chained
// rules, disabled variables, other activation methods, Mamdani and Tsukamoto outputs, and
// Octave's aggregation of equal singletons, and Function terms (formulas).
[[nodiscard]] std::string straight_line_refusal(const fuzzy::EngineModel<double>& model);

// The class template Supervisor<Scalar> (the concept of fuzzypid/supervisor/supervisor.hpp) whose
// infer() computes what fuzzy::evaluate computes on `model`, bit for bit: the same operations in
// the same order, every number the exact literal of the model's converted to Scalar. Rules whose
// strength is 0 are skipped (a run of consecutive rules opened by the same conjunct is skipped as
// a whole when that conjunct is 0), and so are products with a zero constant: neither changes a
// sum. Requires straight_line_refusal(model) to be "".
[[nodiscard]] std::string straight_line_supervisor(const fuzzy::EngineModel<double>& model,
                                                   const SupervisorBinding& binding);

}  // namespace fuzzypid::codegen
