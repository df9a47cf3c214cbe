// Text helpers shared by the .fis and .fll readers and writers (private to fuzzypid::rulefile).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "fuzzypid/fuzzy/engine.hpp"

namespace fuzzypid::io::text {

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
// %.17g, with inf, -inf and nan spelled the way both formats read them.
std::string format_number(double x);
std::string quoted(std::string_view s);
std::string_view name_of(const fuzzy::Name& name);
// Letters, digits, '_' and '.', and not a word of the .fll rule grammar.
bool valid_identifier(std::string_view s);

}  // namespace fuzzypid::io::text
