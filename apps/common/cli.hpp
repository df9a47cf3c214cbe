// The command-line conventions every tool of the project follows, on top of CLI11:
//   - exit codes: 0 success, 1 a run-time failure (bad input data, a write error, a controller
//     fault), 2 a usage error (unknown option, missing or malformed value, value out of range);
//   - numbers are checked before conversion: an unsigned option takes digits only ("-1" is an
//     error, not 2^64 - 1; a value beyond the type's range is an error, not a saturated one), and a
//     real option takes a finite number unless it says otherwise;
//   - an empty value is refused for every option ("omit the option for its default");
//   - an enumerated option is parsed from the table kept next to its enum (the same table gives
//     its to_string), and --help lists the accepted names;
//   - standard output is checked: a write that fails (a full disk, `> /dev/full`) is an error.
#pragma once

#include <sys/stat.h>

#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "fuzzypid/enum_names.hpp"

namespace fuzzypid::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;

// The accepted spellings of an enum's name table (enum_names.hpp), for messages: "a, b or c".
template <class Enum, std::size_t N>
std::string names_listed(const std::array<EnumName<Enum>, N>& table) {
  std::string out;
  for (std::size_t k = 0; k < N; ++k) {
    if (k > 0) out += k + 1 == N ? " or " : ", ";
    out += table[k].name;
  }
  return out;
}

// Adds an option whose value must be one of the table's names; --help lists them.
template <class Enum, std::size_t N>
CLI::Option* add_enum_option(CLI::App& app, const std::string& name, Enum& value,
                             const std::array<EnumName<Enum>, N>& table, const std::string& help) {
  const std::string default_name = name_of(table, value);
  // The validator turns the name into the enumerator's number, which CLI11 then converts.
  CLI::Validator by_name(
      [table](std::string& s) -> std::string {
        if (const std::optional<Enum> e = parse_enum(table, s)) {
          s = std::to_string(static_cast<long long>(*e));
          return {};
        }
        return "'" + s + "' is not " + names_listed(table);
      },
      "");
  return app
      .add_option(name, value,
                  help + " (" + names_listed(table) + "; default " + default_name + ")")
      ->transform(by_name)
      ->option_text("NAME");
}

namespace detail {

inline std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

}  // namespace detail

// Parses a whole string of decimal digits into an unsigned 64-bit integer; nullopt for a sign,
// blanks, other characters or a value beyond 2^64 - 1.
inline std::optional<std::uint64_t> parse_unsigned(const std::string& text) {
  if (text.empty() || text.size() > 20) return std::nullopt;
  for (const char c : text)
    if (c < '0' || c > '9') return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
  if (errno == ERANGE || end != text.c_str() + text.size()) return std::nullopt;
  return static_cast<std::uint64_t>(v);
}

// Parses a whole string as a finite real number (surrounding blanks allowed). An overflow (1e999)
// is not finite; an underflow (1e-320, a subnormal) is, and is kept as strtod reads it (the
// option's range then decides).
inline std::optional<double> parse_finite(const std::string& text) {
  const std::string t = detail::trimmed(text);
  if (t.empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  if (end != t.c_str() + t.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

// Validators applied to the text before CLI11 converts it.
inline CLI::Validator unsigned_integer() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        return parse_unsigned(s) ? std::string() : "'" + s + "' is not an integer in [0, 2^64 - 1]";
      },
      "UINT");
}

// An unsigned integer in [lo, hi].
inline CLI::Validator unsigned_in(std::uint64_t lo, std::uint64_t hi) {
  return CLI::Validator(
      [lo, hi](std::string& s) -> std::string {
        const auto v = parse_unsigned(s);
        if (!v) return "'" + s + "' is not a non-negative integer";
        if (*v < lo || *v > hi)
          return s + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
        return {};
      },
      "UINT in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
}

inline CLI::Validator finite_number() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        return parse_finite(s) ? std::string() : "'" + s + "' is not a finite number";
      },
      "FINITE");
}

// A finite number in [lo, hi].
inline CLI::Validator finite_in(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& s) -> std::string {
        const auto v = parse_finite(s);
        if (!v) return "'" + s + "' is not a finite number";
        if (*v < lo || *v > hi)
          return s + " is outside [" + CLI::detail::to_string(lo) + ", " +
                 CLI::detail::to_string(hi) + "]";
        return {};
      },
      "in [" + CLI::detail::to_string(lo) + ", " + CLI::detail::to_string(hi) + "]");
}

// An empty value never stands for the default: `--urdf ''` (a variable that expanded to nothing)
// is refused, naming the option, instead of silently running the bundled robot.
inline CLI::Validator non_empty() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        return s.empty() ? "empty value (omit the option for its default)" : std::string();
      },
      "");
}

// Adds non_empty() to every option of `app` and of its subcommands that takes a value (flags take
// none), after the option's own checks. Called by the parsers before they parse.
inline void refuse_empty_values(CLI::App& app) {
  for (CLI::Option* option : app.get_options())
    if (option->get_type_size() != 0 && option->get_expected_max() != 0) option->check(non_empty());
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    refuse_empty_values(*sub);
}

// The options a command line gave (their long names, "--out"), kept after parsing so that checks
// of combinations can run later, and the one refusal of an option that would do nothing: every
// tool refuses an option that its other options make meaningless instead of ignoring it.
class GivenOptions {
 public:
  GivenOptions() = default;
  explicit GivenOptions(const CLI::App& app) {
    for (const CLI::Option* o : app.get_options())
      if (o->count() > 0) names_.push_back(o->get_name());
  }
  [[nodiscard]] bool has(std::string_view name) const {
    for (const std::string& n : names_)
      if (n == name) return true;
    return false;
  }
  // "NAME applies only to SCOPE; REASON" for the first of `names` given, else "" (also when
  // `applies`: the combination is meaningful).
  [[nodiscard]] std::string refuse_unused(std::initializer_list<std::string_view> names,
                                          bool applies, const std::string& scope,
                                          const std::string& reason) const {
    if (applies) return {};
    for (const std::string_view name : names)
      if (has(name)) return std::string(name) + " applies only to " + scope + "; " + reason;
    return {};
  }
  [[nodiscard]] const std::vector<std::string>& names() const noexcept { return names_; }

 private:
  std::vector<std::string> names_;
};

// Runs a tool's main body, turning an exception that escapes it (an allocation failure, a bug) into
// a message and kExitFailure instead of std::terminate. A run whose messages on standard error did
// not all reach it (2>/dev/full: a warning or a report lost unseen) exits kExitFailure too.
template <class Body>
int run_main(const char* tool, Body&& body) noexcept {
  int code = kExitFailure;
  try {
    code = body();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", tool, e.what());
  } catch (...) {
    std::fprintf(stderr, "%s: unknown exception\n", tool);
  }
  return code == kExitOk && std::ferror(stderr) != 0 ? kExitFailure : code;
}

// Parses the command line. Returns nullopt when the tool should run, else the exit code: 0 after
// --help (printed to stdout), kExitUsage after a usage error (message on stderr).
inline std::optional<int> parse(CLI::App& app, int argc, const char* const* argv) {
  refuse_empty_values(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  }
  return std::nullopt;
}

// Standard input must be readable data: refuses a directory up front (a read of one fails, and
// would otherwise look like empty input). Returns an error message or an empty string.
inline std::string check_stdin_is_data() {
  struct stat st {};
  if (::fstat(0, &st) != 0)
    return std::string("standard input is not open: ") + std::strerror(errno);
  if (S_ISDIR(st.st_mode)) return "standard input is a directory";
  return {};
}

// After reading standard input to its end: a read error (e.g. stdin open for writing only) is
// reported instead of passing for the end of the input.
inline std::string stdin_read_error() {
  if (std::ferror(stdin) != 0) return "cannot read standard input";
  return {};
}

// Flushes standard output and reports whether every write reached it. Returns kExitOk or, after a
// message on stderr naming the tool, kExitFailure.
inline int finish_stdout(const char* tool) {
  errno = 0;
  const bool flushed = std::fflush(stdout) == 0;
  const int err = errno;
  if (flushed && std::ferror(stdout) == 0) return kExitOk;
  std::fprintf(stderr, "%s: cannot write standard output%s%s\n", tool, err != 0 ? ": " : "",
               err != 0 ? std::strerror(err) : "");
  return kExitFailure;
}

}  // namespace fuzzypid::cli
