// Strict CSV input and %.17g output for the command-line tools.
//
// Rows are comma-separated numbers. Blank lines and lines starting with '#' are skipped. The first
// non-blank line may be a header: it is skipped when every one of its fields is text, i.e. not a
// number as strtod reads one (so "nan", "inf" and "1e999" are numbers -- not finite, hence errors
// -- and never pass for a header), nor a number in double quotes ("0.5", as spreadsheets export
// it: an error naming the quotes, never a header that silently drops the first row). A number
// that underflows (1e-320, a subnormal) is finite and kept as strtod reads it. Every other malformed row is an error whose message names the
// line, so a user piping a file through a tool learns exactly where it is wrong. Lines are read
// with a bound (kMaxLineBytes): a longer line is an error, not an unbounded allocation.
#pragma once

#include <cerrno>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <istream>
#include <streambuf>
#include <string>
#include <vector>

#include "fuzzypid_support/printable.hpp"

namespace fuzzypid::cli {

struct CsvRow {
  std::size_t line = 0;        // 1-based line number in the input
  std::vector<double> values;  // the parsed fields, all finite
};

class CsvReader {
 public:
  // Longest accepted line in bytes (without the newline). A row of the tools is at most 18
  // numbers of some 25 characters.
  static constexpr std::size_t kMaxLineBytes = 64 * 1024;

  explicit CsvReader(std::istream& in) : in_(in) {}

  // Reads the next data row. Returns false at the end of input or on error; error() is empty at
  // the end of input and names the line otherwise.
  bool next(CsvRow& row) {
    std::string text;
    for (;;) {
      const LineRead got = read_line(text);
      if (got == LineRead::End) return false;
      ++line_;
      if (got == LineRead::TooLong) {
        error_ = "line " + std::to_string(line_) + ": longer than " +
                 std::to_string(kMaxLineBytes) + " bytes";
        return false;
      }
      if (!text.empty() && text.back() == '\r') text.pop_back();
      if (is_blank(text) || text[0] == '#') continue;
      std::vector<std::string> fields = split(text);
      row.line = line_;
      row.values.clear();
      bool all_text = true;
      std::string first_bad;
      for (std::size_t k = 0; k < fields.size(); ++k) {
        double v = 0.0;
        const Field kind = parse_field(fields[k], v);
        if (kind != Field::Text) all_text = false;
        if (kind != Field::Finite && first_bad.empty())
          first_bad = "column " + std::to_string(k + 1) + " ('" + shown(fields[k]) + "')" +
                      (kind == Field::Quoted ? " is a number in quotes: write it without them"
                                             : " is not a finite number");
        row.values.push_back(v);
      }
      if (!seen_data_ && all_text) {  // header line
        seen_data_ = true;
        continue;
      }
      seen_data_ = true;
      if (!first_bad.empty()) {
        error_ = "line " + std::to_string(line_) + ": " + first_bad;
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
  }

  // Requires every data row to have between min_columns and max_columns fields.
  void expect_columns(std::size_t min_columns, std::size_t max_columns) {
    expected_columns_min_ = min_columns;
    expected_columns_max_ = max_columns;
  }

  const std::string& error() const { return error_; }

 private:
  enum class LineRead { Line, TooLong, End };
  // A field is a finite number, another number (NaN, inf, out of range), a number in double quotes,
  // or text (a header).
  enum class Field { Finite, NotFinite, Quoted, Text };

  // Reads up to the next '\n' (not stored). At the end of the input sets the stream's eofbit.
  LineRead read_line(std::string& text) {
    using Traits = std::char_traits<char>;
    text.clear();
    std::streambuf* buffer = in_.rdbuf();
    if (buffer == nullptr) return LineRead::End;
    bool any = false;
    for (;;) {
      const Traits::int_type c = buffer->sbumpc();
      if (Traits::eq_int_type(c, Traits::eof())) {
        in_.setstate(std::ios::eofbit);
        return any ? LineRead::Line : LineRead::End;
      }
      any = true;
      if (Traits::to_char_type(c) == '\n') return LineRead::Line;
      if (text.size() >= kMaxLineBytes) return LineRead::TooLong;
      text.push_back(Traits::to_char_type(c));
    }
  }

  static bool is_blank(const std::string& s) {
    return s.find_first_not_of(" \t") == std::string::npos;
  }
  static std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t");
    if (b == std::string::npos) return {};
    const auto e = s.find_last_not_of(" \t");
    return s.substr(b, e - b + 1);
  }
  // The field as quoted in a message: trimmed, at most 40 bytes, non-printable bytes escaped.
  static std::string shown(const std::string& field) {
    const std::string t = trim(field);
    return support::printable(t.size() <= 40 ? t : t.substr(0, 40) + "...");
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
  // A number is a field strtod reads completely (surrounding blanks allowed); it is Finite when
  // its value is finite: an overflow (1e999) is not, an underflow (1e-320) is the subnormal or zero
  // strtod gives. Quoted is such a number in double quotes. Text is any other non-empty field; an
  // empty field is neither a number nor a header name.
  static Field parse_field(const std::string& field, double& value) {
    const std::string t = trim(field);
    if (t.empty()) return Field::NotFinite;
    if (t.size() > 2 && t.front() == '"' && t.back() == '"') {
      double inner = 0.0;
      if (parse_field(t.substr(1, t.size() - 2), inner) != Field::Text) return Field::Quoted;
    }
    const char* begin = t.c_str();
    char* end = nullptr;
    value = std::strtod(begin, &end);
    if (end != begin + t.size()) return Field::Text;
    return std::isfinite(value) ? Field::Finite : Field::NotFinite;
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

// Writes one CSV line of numbers with round-trip precision. Write errors are sticky in the stream
// (ferror); the tools check them once at the end (cli::finish_stdout).
inline void write_row(std::FILE* out, const double* values, std::size_t count) {
  for (std::size_t k = 0; k < count; ++k)
    std::fprintf(out, k == 0 ? "%.17g" : ",%.17g", values[k]);
  std::fputc('\n', out);
}

}  // namespace fuzzypid::cli
