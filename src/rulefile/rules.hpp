// The rule grammar shared by .fll and .fcl files (fuzzylite's), read into and written from the
// engine's postfix form (private to fuzzypid::rulefile):
//
//   rule        := "if" expression "then" conclusion {"and" conclusion} ["with" weight]
//   expression  := conjunction {"or" conjunction}          (left to right)
//   conjunction := primary {"and" primary}                 ("and" binds tighter than "or")
//   primary     := "(" expression ")" | variable "is" {hedge} (term | "any")
//                  (an input, or an output: chained systems, see fuzzy/engine.hpp)
//   conclusion  := output "is" {hedge} term
//   hedge       := "not" | "seldom" | "somewhat" | "very" | "extremely" | "any"
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "check.hpp"
#include "fuzzypid/rulefile/rule_file.hpp"

namespace fuzzypid::rulefile::rules {

// Which term a name means when several terms of a variable share it: the first (fuzzylite 6's
// Variable::getTerm; .fcl) or the last (fuzzylite 8, whose variables look terms up by name in a
// map filled in file order; .fll).
enum class DuplicateTerm { First, Last };

// Parses one rule and appends it to `model` in block `block`. Keywords and hedges are matched in
// any case when `any_case` (FCL), else in lower case (fuzzylite). Returns an empty string on
// success, else the reason naming the offending word.
std::string parse_rule(std::string_view text, Builder& model, std::size_t block, bool any_case,
                       DuplicateTerm duplicate = DuplicateTerm::First);

// The names variables and terms get in .fll/.fcl text: sanitised the way fuzzylite does (only
// letters, digits, '_' and '.'), "unnamed" when nothing is left, '_' appended to a rule keyword or
// hedge, and "_2", "_3", ... appended where two names would otherwise coincide (variables among
// themselves; terms within their variable).
struct ExportNames {
  std::vector<std::string> inputs, outputs;
  std::vector<std::vector<std::string>> input_terms, output_terms;
};
ExportNames export_names(const Model& model);

// The rule as text in the grammar above, with the export names.
std::string write_rule(const Model& model, std::size_t r, const ExportNames& names);

}  // namespace fuzzypid::rulefile::rules
