// Formulas of fuzzylite's Function terms: fuzzylite 8's infix grammar compiled into the engine
// model's pool of formula steps (fuzzy/formula.hpp), and written back (private to
// fuzzypid::rulefile; docs/rule_files.md, "Function terms").
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "check.hpp"

namespace fuzzypid::rulefile::formula {

// The longest formula text read (bytes).
inline constexpr std::size_t kMaxFormulaLength = 4096;

// A Function term read before every variable is known (a formula may name an input declared
// later): compiled by compile_all() once the variables are read.
struct Pending {
  bool input = true;  // an input's term (x allowed), else a Takagi-Sugeno output's (x refused)
  std::size_t variable = 0;
  std::size_t term = 0;
  std::string name;  // the term's
  std::string text;
  int line = 0;
};

// Compiles `text` at the end of model.steps and points `term` (Shape::Function) at it. `x_allowed`:
// the formula may read x (input terms). Names are the model's inputs (their values) and outputs
// (refused). Empty on success, else the reason.
std::string compile(std::string_view text, bool x_allowed, Builder& model,
                    fuzzy::Term<double>& term);

// Compiles every pending formula into its term (input terms, or output terms made
// OutputTermKind::Function); on the first failure sets error.line and error.message, false.
bool compile_all(const std::vector<Pending>& pending, Builder& model, LoadError& error);

// The formula of a Function term as fully parenthesised infix text that fuzzylite 8 and compile()
// read back to the same steps; empty when a constant has no such form (NaN, infinite).
std::string write(const fuzzy::Term<double>& term, const Model& model);

}  // namespace fuzzypid::rulefile::formula
