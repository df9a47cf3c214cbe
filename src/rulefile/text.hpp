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

// `text` without a leading UTF-8 byte-order mark (Windows editors write one).
std::string_view without_bom(std::string_view text);
// Splits on '\n' (a trailing '\r' is dropped).
std::vector<Line> split_lines(std::string_view text);
std::string_view trim(std::string_view s);
// Splits on spaces and tabs, dropping empty pieces.
std::vector<std::string_view> split_words(std::string_view s);
// A whole-token number: decimal or exponent notation, inf/-inf (any case); false otherwise.
// NaN is accepted only when allow_nan.
bool parse_number(std::string_view s, double& value, bool allow_nan = false);
// A constant expression as MATLAB evaluates it, the way a .fis may write a range's bounds
// (MATLAB's readfis evaluates them: `Range=[-pi/4 pi/4]`): numbers, pi, Inf, + - * / ^, unary
// + and -, parentheses, and the functions sqrt exp log log10 log2 abs sin cos tan asin acos atan
// sinh cosh tanh floor ceil round fix. MATLAB's precedence: ^ (left to right) above unary minus
// (-2^2 is -4) above * / above + -. False, with the reason in `why`, on anything else.
bool evaluate_matlab_constant(std::string_view s, double& value, std::string& why);
// The elements of the inside of a MATLAB row `[a b c]`, as MATLAB splits it: at commas, and at
// blanks outside parentheses that stand between two operands ("-pi/4 pi/4" is two elements,
// "1 - 2" one, "1 -2" two).
std::vector<std::string_view> matlab_row_elements(std::string_view inner);
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
