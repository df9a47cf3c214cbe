// Strict CSV input and %.17g output for the command-line tools.
//
// Rows are comma-separated numbers. Blank lines and lines starting with '#' are skipped. The first
// non-blank line may be a header: it is skipped when none of its fields parses as a number. Every
// other malformed row is an error whose message names the line, so a user piping a file through a
// tool learns exactly where it is wrong.
#pragma once

#include <cerrno>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <istream>
#include <string>
#include <vector>

namespace fuzzypid::cli {

struct CsvRow {
  std::size_t line = 0;        // 1-based line number in the input
  std::vector<double> values;  // the parsed fields, all finite
};

class CsvReader {
 public:
  explicit CsvReader(std::istream& in) : in_(in) {}

  // Reads the next data row. Returns false at the end of input or on error; error() is empty at
  // the end of input and names the line otherwise.
  bool next(CsvRow& row) {
    std::string text;
    while (std::getline(in_, text)) {
      ++line_;
      if (!text.empty() && text.back() == '\r') text.pop_back();
      if (is_blank(text) || text[0] == '#') continue;
      std::vector<std::string> fields = split(text);
      row.line = line_;
      row.values.clear();
      std::size_t parsed = 0;
      std::string first_bad;
      for (std::size_t k = 0; k < fields.size(); ++k) {
        double v = 0.0;
        if (parse_number(fields[k], v)) {
          ++parsed;
        } else if (first_bad.empty()) {
          first_bad = "column " + std::to_string(k + 1) + " ('" + trim(fields[k]) + "')";
        }
        row.values.push_back(v);
      }
      if (!seen_data_ && parsed == 0) {  // header line
        seen_data_ = true;
        continue;
      }
      seen_data_ = true;
      if (!first_bad.empty()) {
        error_ = "line " + std::to_string(line_) + ": " + first_bad + " is not a finite number";
        return false;
      }
      if (expected_columns_min_ != 0 && (row.values.size() < expected_columns_min_ ||
                                         row.values.size() > expected_columns_max_)) {
        error_ = "line " + std::to_string(line_) + ": expected " + columns_text() + ", got " +
                 std::to_string(row.values.size());
        return false;
      }
      return true;
    }
    return false;
  }

  // Requires every data row to have between min_columns and max_columns fields.
  void expect_columns(std::size_t min_columns, std::size_t max_columns) {
    expected_columns_min_ = min_columns;
    expected_columns_max_ = max_columns;
  }

  const std::string& error() const { return error_; }

 private:
  static bool is_blank(const std::string& s) {
    return s.find_first_not_of(" \t") == std::string::npos;
  }
  static std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t");
    if (b == std::string::npos) return {};
    const auto e = s.find_last_not_of(" \t");
    return s.substr(b, e - b + 1);
  }
  static std::vector<std::string> split(const std::string& s) {
    std::vector<std::string> out;
    std::size_t start = 0;
    for (;;) {
      const auto comma = s.find(',', start);
      out.push_back(
          s.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
    return out;
  }
  // Accepts a complete finite decimal number, surrounded by optional blanks.
  static bool parse_number(const std::string& field, double& value) {
    const std::string t = trim(field);
    if (t.empty()) return false;
    const char* begin = t.c_str();
    char* end = nullptr;
    errno = 0;
    value = std::strtod(begin, &end);
    if (end != begin + t.size() || errno == ERANGE) return false;
    return std::isfinite(value);
  }
  std::string columns_text() const {
    if (expected_columns_min_ == expected_columns_max_)
      return std::to_string(expected_columns_min_) + " columns";
    return std::to_string(expected_columns_min_) + " or " + std::to_string(expected_columns_max_) +
           " columns";
  }

  std::istream& in_;
  std::size_t line_ = 0;
  bool seen_data_ = false;
  std::size_t expected_columns_min_ = 0;
  std::size_t expected_columns_max_ = 0;
  std::string error_;
};

// Writes one CSV line of numbers with round-trip precision.
inline void write_row(std::FILE* out, const double* values, std::size_t count) {
  for (std::size_t k = 0; k < count; ++k)
    std::fprintf(out, k == 0 ? "%.17g" : ",%.17g", values[k]);
  std::fputc('\n', out);
}

}  // namespace fuzzypid::cli
