// Text helpers shared by the .fis, .fll and .fcl readers and writers (private to
// fuzzypid::rulefile).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "fuzzypid/rulefile/rule_file.hpp"

namespace fuzzypid::rulefile::text {

// One line of the input with its 1-based number.
struct Line {
  int number = 0;
  std::string_view text;
};

// Splits on '\n' (a trailing '\r' is dropped).
std::vector<Line> split_lines(std::string_view text);
std::string_view trim(std::string_view s);
// Splits on spaces and tabs, dropping empty pieces.
std::vector<std::string_view> split_words(std::string_view s);
// A whole-token number: decimal or exponent notation, inf/-inf (any case); false otherwise.
// NaN is accepted only when allow_nan.
bool parse_number(std::string_view s, double& value, bool allow_nan = false);
// A whole-token non-negative integer.
bool parse_count(std::string_view s, std::size_t& value);
// %.17g, with inf, -inf and nan spelled the way the formats read them.
std::string format_number(double x);
std::string quoted(std::string_view s);
std::string_view name_of(const fuzzy::Name& name);
// fuzzylite's Op::validName: keeps letters, digits, '_' and '.'; "unnamed" when nothing is left.
std::string sanitized(std::string_view name);
// Letters, digits, '_' and '.'.
bool is_identifier(std::string_view s);
// A word of the rule grammar (if is not and or then with) or a hedge.
bool is_reserved(std::string_view s);
std::string lower(std::string_view s);
bool iequals(std::string_view a, std::string_view b);

}  // namespace fuzzypid::rulefile::text
