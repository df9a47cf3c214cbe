// The rule base of a controller file's `[supervisor] rule_file` as C++ for export-header: constexpr
// data of a fixed-capacity fuzzy::EngineModel sized to the file, and the supervisor FuzzyPid calls,
// so the target needs no parser and no heap.
#pragma once

#include <string>

#include "fuzzypid/fuzzy/engine_model.hpp"

namespace fuzzypid::codegen {

// An exact C++ literal of v converted to the generated code's `Scalar` (hexadecimal floating
// point; infinities and NaN through std::numeric_limits<Scalar>).
[[nodiscard]] std::string scalar_literal(double v);

// "" when every number of `model` is finite after conversion to float or infinite in the file
// (open ranges), else the first that a float would turn infinite.
[[nodiscard]] std::string check_rule_base_float_range(const fuzzy::EngineModel<double>& model);

// Defines, inside the generated namespace: RuleBaseCapacity (the file's exact counts),
// make_rule_base<Scalar>() and kRuleBase<Scalar> (the model, constexpr, every number an exact
// hexadecimal literal of the loaded double converted to Scalar), and Supervisor<Scalar> with
// kSupervisor<Scalar>: e, ec in, dKp, dKi, dKd out, as supervisor::EngineSupervisor computes them.
// The supervisor is straight-line code (straight_line_supervisor.hpp) where the generator covers
// the model, else fuzzy::evaluate on a fixed EngineWorkspace, with the reason in a comment.
// `model` must be valid with 2 inputs and 3 outputs named as a supervisor's; `rule_file` is named
// in a comment.
[[nodiscard]] std::string export_rule_base(const fuzzy::EngineModel<double>& model,
                                           const std::string& rule_file);

}  // namespace fuzzypid::codegen
