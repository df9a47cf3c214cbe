// The rule grammar shared by .fll and .fcl files (fuzzylite's), read into and written from the
// engine's postfix form (private to fuzzypid::rulefile):
//
//   rule        := "if" expression "then" conclusion {"and" conclusion} ["with" weight]
//   expression  := conjunction {"or" conjunction}          (left to right)
//   conjunction := primary {"and" primary}                 ("and" binds tighter than "or")
//   primary     := "(" expression ")" | input "is" {hedge} (term | "any")
//   conclusion  := output "is" {hedge} term
//   hedge       := "not" | "seldom" | "somewhat" | "very" | "extremely" | "any"
#pragma once

#include <string>
#include <string_view>

#include "fuzzypid/rulefile/rule_file.hpp"

namespace fuzzypid::rulefile::rules {

// Parses one rule and appends it to `model` in block `block`. Keywords and hedges are matched in
// any case when `any_case` (FCL), else in lower case (fuzzylite). Returns an empty string on
// success, else the reason naming the offending word.
std::string parse_rule(std::string_view text, Model& model, std::size_t block, bool any_case);

// The rule as text in the grammar above, with names sanitised for .fll/.fcl.
std::string write_rule(const Model& model, std::size_t r);

// The name a variable or term has in .fll/.fcl text.
std::string fll_name(const fuzzy::Name& name);

}  // namespace fuzzypid::rulefile::rules
