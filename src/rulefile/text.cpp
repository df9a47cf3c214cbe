#include "text.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace fuzzypid::rulefile::text {

std::string_view without_bom(std::string_view text) {
  return text.substr(0, 3) == "\xEF\xBB\xBF" ? text.substr(3) : text;
}

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

namespace {

// Recursive descent over MATLAB's grammar of constant expressions (see text.hpp):
//   sum     := product {('+' | '-') product}
//   product := unary {('*' | '/') unary}
//   unary   := ('+' | '-') unary | power
//   power   := primary {'^' ('+' | '-')* primary}        (left to right, as MATLAB)
//   primary := number | name | name '(' sum ')' | '(' sum ')'
class MatlabConstant {
 public:
  explicit MatlabConstant(std::string_view s) : s_(s) {}

  bool evaluate(double& value, std::string& why) {
    if (!sum(value)) {
      why = why_.empty() ? "not an expression" : why_;
      return false;
    }
    skip();
    if (k_ != s_.size()) {
      why = "unexpected '" + std::string(s_.substr(k_)) + "'";
      return false;
    }
    return true;
  }

 private:
  void skip() {
    while (k_ < s_.size() && (s_[k_] == ' ' || s_[k_] == '\t'))
      ++k_;
  }
  bool take(char c) {
    skip();
    if (k_ < s_.size() && s_[k_] == c) {
      ++k_;
      return true;
    }
    return false;
  }
  bool sum(double& v) {
    if (!product(v)) return false;
    for (;;) {
      double b = 0;
      if (take('+')) {
        if (!product(b)) return false;
        v += b;
      } else if (take('-')) {
        if (!product(b)) return false;
        v -= b;
      } else {
        return true;
      }
    }
  }
  bool product(double& v) {
    if (!unary(v)) return false;
    for (;;) {
      double b = 0;
      if (take('*')) {
        if (!unary(b)) return false;
        v *= b;
      } else if (take('/')) {
        if (!unary(b)) return false;
        v /= b;
      } else {
        return true;
      }
    }
  }
  bool unary(double& v) {
    if (take('-')) {
      if (!unary(v)) return false;
      v = -v;
      return true;
    }
    if (take('+')) return unary(v);
    return power(v);
  }
  bool power(double& v) {
    if (!primary(v)) return false;
    while (take('^')) {
      // MATLAB reads 2^-1 as 2^(-1): signs right after ^ belong to its operand.
      double sign = 1;
      for (;;) {
        if (take('-'))
          sign = -sign;
        else if (!take('+'))
          break;
      }
      double b = 0;
      if (!primary(b)) return false;
      v = std::pow(v, sign * b);
    }
    return true;
  }
  bool primary(double& v) {
    skip();
    if (take('(')) return sum(v) && (take(')') || fail("missing ')'"));
    const std::size_t b = k_;
    if (k_ < s_.size() && (std::isdigit(static_cast<unsigned char>(s_[k_])) || s_[k_] == '.')) {
      while (k_ < s_.size() && (std::isdigit(static_cast<unsigned char>(s_[k_])) || s_[k_] == '.'))
        ++k_;
      if (k_ < s_.size() && (s_[k_] == 'e' || s_[k_] == 'E')) {
        std::size_t e = k_ + 1;
        if (e < s_.size() && (s_[e] == '+' || s_[e] == '-')) ++e;
        if (e < s_.size() && std::isdigit(static_cast<unsigned char>(s_[e]))) {
          k_ = e;
          while (k_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[k_])))
            ++k_;
        }
      }
      return parse_number(s_.substr(b, k_ - b), v) || fail("bad number");
    }
    while (k_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[k_])) || s_[k_] == '_'))
      ++k_;
    const std::string_view name = s_.substr(b, k_ - b);
    if (name.empty()) return fail("expected a number, a name or '('");
    if (take('(')) {
      double x = 0;
      if (!sum(x) || !(take(')') || fail("missing ')'"))) return false;
      return call(name, x, v);
    }
    if (name == "pi") {
      v = 3.141592653589793;  // M_PI, MATLAB's pi
      return true;
    }
    if (name == "Inf" || name == "inf") {
      v = std::numeric_limits<double>::infinity();
      return true;
    }
    return fail("unknown name '" + std::string(name) + "'");
  }
  bool call(std::string_view f, double x, double& v) {
    using Fn = double (*)(double);
    static constexpr struct {
      const char* name;
      Fn fn;
    } kFunctions[] = {
        {"sqrt", [](double a) { return std::sqrt(a); }},
        {"exp", [](double a) { return std::exp(a); }},
        {"log", [](double a) { return std::log(a); }},
        {"log10", [](double a) { return std::log10(a); }},
        {"log2", [](double a) { return std::log2(a); }},
        {"abs", [](double a) { return std::fabs(a); }},
        {"sin", [](double a) { return std::sin(a); }},
        {"cos", [](double a) { return std::cos(a); }},
        {"tan", [](double a) { return std::tan(a); }},
        {"asin", [](double a) { return std::asin(a); }},
        {"acos", [](double a) { return std::acos(a); }},
        {"atan", [](double a) { return std::atan(a); }},
        {"sinh", [](double a) { return std::sinh(a); }},
        {"cosh", [](double a) { return std::cosh(a); }},
        {"tanh", [](double a) { return std::tanh(a); }},
        {"floor", [](double a) { return std::floor(a); }},
        {"ceil", [](double a) { return std::ceil(a); }},
        {"round", [](double a) { return std::round(a); }},  // half away from zero, as MATLAB
        {"fix", [](double a) { return std::trunc(a); }},
    };
    for (const auto& fn : kFunctions)
      if (f == fn.name) {
        v = fn.fn(x);
        return true;
      }
    return fail("unknown function '" + std::string(f) + "'");
  }
  bool fail(std::string why) {
    if (why_.empty()) why_ = std::move(why);
    return false;
  }

  std::string_view s_;
  std::size_t k_ = 0;
  std::string why_;
};

bool ends_operand(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == ')';
}

}  // namespace

bool evaluate_matlab_constant(std::string_view s, double& value, std::string& why) {
  return MatlabConstant(s).evaluate(value, why);
}

std::vector<std::string_view> matlab_row_elements(std::string_view inner) {
  std::vector<std::string_view> out;
  std::size_t start = 0, depth = 0;
  const auto push = [&](std::size_t end) {
    std::string_view e = inner.substr(start, end - start);
    while (!e.empty() && (e.front() == ' ' || e.front() == '\t'))
      e.remove_prefix(1);
    while (!e.empty() && (e.back() == ' ' || e.back() == '\t'))
      e.remove_suffix(1);
    if (!e.empty()) out.push_back(e);
  };
  for (std::size_t k = 0; k < inner.size(); ++k) {
    const char c = inner[k];
    if (c == '(') ++depth;
    if (c == ')' && depth > 0) --depth;
    if (depth == 0 && c == ',') {
      push(k);
      start = k + 1;
      continue;
    }
    if (depth != 0 || (c != ' ' && c != '\t')) continue;
    // A blank between an operand and the start of another one separates two elements; a sign
    // starts one only when no blank follows it (MATLAB: [1 -2] is two elements, [1 - 2] one).
    std::size_t b = k;
    while (b > start && (inner[b - 1] == ' ' || inner[b - 1] == '\t'))
      --b;
    std::size_t n = k;
    while (n < inner.size() && (inner[n] == ' ' || inner[n] == '\t'))
      ++n;
    if (b == start || n == inner.size() || !ends_operand(inner[b - 1])) continue;
    const char next = inner[n];
    const bool sign = (next == '-' || next == '+') && n + 1 < inner.size() && inner[n + 1] != ' ' &&
                      inner[n + 1] != '\t';
    const bool starts = std::isalnum(static_cast<unsigned char>(next)) || next == '_' ||
                        next == '.' || next == '(' || sign;
    if (starts) {
      push(k);
      start = n;
      k = n - 1;
    }
  }
  push(inner.size());
  return out;
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
