#include "text.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace fuzzypid::rulefile::text {

std::vector<Line> split_lines(std::string_view text) {
  std::vector<Line> lines;
  int number = 1;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back({number++, line});
    if (end == text.size()) break;
    start = end + 1;
  }
  return lines;
}

std::string_view trim(std::string_view s) {
  const char* ws = " \t\r\n\f\v";
  const std::size_t b = s.find_first_not_of(ws);
  if (b == std::string_view::npos) return {};
  const std::size_t e = s.find_last_not_of(ws);
  return s.substr(b, e - b + 1);
}

std::vector<std::string_view> split_words(std::string_view s) {
  std::vector<std::string_view> words;
  std::size_t k = 0;
  while (k < s.size()) {
    while (k < s.size() && (s[k] == ' ' || s[k] == '\t'))
      ++k;
    const std::size_t b = k;
    while (k < s.size() && s[k] != ' ' && s[k] != '\t')
      ++k;
    if (k > b) words.push_back(s.substr(b, k - b));
  }
  return words;
}

bool parse_number(std::string_view s, double& value, bool allow_nan) {
  if (s.empty() || s.size() > 64) return false;
  char buffer[65];
  std::memcpy(buffer, s.data(), s.size());
  buffer[s.size()] = '\0';
  // strtod also reads hexadecimal and "infinity"; restrict to what the formats write.
  for (std::size_t k = 0; k < s.size(); ++k) {
    const char c = buffer[k];
    if (c == 'x' || c == 'X' || c == '(' || c == ')') return false;
  }
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(buffer, &end);
  if (end != buffer + s.size()) return false;
  if (std::isnan(v) && !allow_nan) return false;
  // Overflow ("1e999") is an error; underflow to a subnormal or zero is kept as read.
  if (errno == ERANGE && std::isinf(v)) return false;
  value = v;
  return true;
}

bool parse_count(std::string_view s, std::size_t& value) {
  if (s.empty() || s.size() > 9) return false;
  std::size_t v = 0;
  for (char c : s) {
    if (c < '0' || c > '9') return false;
    v = v * 10 + static_cast<std::size_t>(c - '0');
  }
  value = v;
  return true;
}

std::string format_number(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

std::string quoted(std::string_view s) {
  return "'" + std::string(s) + "'";
}

std::string_view name_of(const fuzzy::Name& name) {
  return std::string_view(name.data());
}

bool is_identifier(std::string_view s) {
  if (s.empty()) return false;
  for (char c : s) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '.';
    if (!ok) return false;
  }
  return true;
}

bool is_reserved(std::string_view s) {
  static const char* const reserved[] = {"if",   "is",  "not",       "and",    "or",       "then",
                                         "with", "any", "extremely", "seldom", "somewhat", "very"};
  for (const char* r : reserved)
    if (s == r) return true;
  return false;
}

std::string sanitized(std::string_view name) {
  std::string out;
  for (char c : name)
    if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
        c == '.')
      out += c;
  return trim(name).empty() ? std::string("unnamed") : out;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return out;
}

bool iequals(std::string_view a, std::string_view b) {
  return lower(a) == lower(b);
}

}  // namespace fuzzypid::rulefile::text
