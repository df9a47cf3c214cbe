// Strict reading of the project's TOML files (controller files, condition sets) on top of toml++:
// every key must be known, every value of the right type and finite unless stated, and every error
// names `file:line:column`. Set-up code only (allocates, uses toml++'s exceptions internally).
#pragma once

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <type_traits>

#include <toml++/toml.h>

#include "fuzzypid/controller_file/controller_file.hpp"

namespace fuzzypid::controller_file {

// Thrown by the reader; callers convert it to an Error at their API boundary.
struct ReadError {
  Error error;
};

class TableReader {
 public:
  TableReader(const toml::table& table, std::string file) : table_(table), file_(std::move(file)) {}

  bool has(std::string_view key) const { return table_.contains(key); }

  // Required when `fallback` is empty.
  double number(std::string_view key, std::optional<double> fallback = std::nullopt,
                bool allow_infinite = false);
  std::uint64_t count(std::string_view key, std::optional<std::uint64_t> fallback = std::nullopt);
  std::string text(std::string_view key, std::optional<std::string> fallback = std::nullopt);
  bool flag(std::string_view key, std::optional<bool> fallback = std::nullopt);
  std::array<double, 3> triple(std::string_view key, std::optional<std::array<double, 3>> fallback,
                               bool allow_infinite = false);
  template <class Enum, std::size_t N>
  Enum choice(std::string_view key, const std::array<EnumName<Enum>, N>& names,
              std::optional<std::common_type_t<Enum>> fallback = std::nullopt) {
    const toml::node* node = find(key, fallback.has_value());
    if (node == nullptr) return *fallback;
    const auto* s = node->as_string();
    if (s == nullptr) fail(*node, "'" + std::string(key) + "' must be a string");
    const auto value = parse_enum(names, s->get());
    if (!value)
      fail(*node, "'" + std::string(key) + "': unknown value '" + s->get() + "' (expected " +
                      names_of(names) + ")");
    return *value;
  }
  // A sub-table; nullopt when absent and not required.
  std::optional<TableReader> table(std::string_view key, bool required);
  const toml::array* array(std::string_view key, bool required);

  // Fails on the first key that no getter asked for.
  void finish() const;

  [[noreturn]] void fail(const toml::node& node, const std::string& message) const;
  [[noreturn]] void fail_here(const std::string& message) const;  // at the table itself
  const std::string& file() const noexcept { return file_; }
  const toml::table& raw() const noexcept { return table_; }

 private:
  const toml::node* find(std::string_view key, bool optional);

  const toml::table& table_;
  std::string file_;
  std::set<std::string, std::less<>> used_;
};

// Reads a double from any numeric node; fails on NaN and (unless allowed) on infinities.
double number_of(const TableReader& where, const toml::node& node, const std::string& what,
                 bool allow_infinite = false);

// Parses `text` into a table or throws ReadError with the parser's position.
toml::table parse_toml(std::string_view text, const std::string& source);
// Reads a whole file (ReadError when it cannot be read).
std::string read_text(const std::string& path);

}  // namespace fuzzypid::controller_file
