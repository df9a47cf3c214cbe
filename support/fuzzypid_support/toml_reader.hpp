// Strict reading of the project's TOML files (controller files, condition files) on top of toml++:
// every key must be known, every value of the right type and finite unless stated, and every error
// names `file:line:column`. Set-up code only (allocates, uses toml++'s exceptions internally).
// Private to the parts that read TOML (controller_file, sim): not a public header, never
// installed, so toml++ never reaches a user's include path.
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <type_traits>

#include <toml++/toml.h>

#include "fuzzypid/enum_names.hpp"
#include "fuzzypid/file_error.hpp"
#include "fuzzypid_support/bounded_read.hpp"

namespace fuzzypid::support {

// Thrown by the reader; callers convert it to an Error at their API boundary.
struct ReadError {
  FileError error;
};

class TableReader {
 public:
  TableReader(const toml::table& table, std::string file) : table_(table), file_(std::move(file)) {}

  bool has(std::string_view key) const { return table_.contains(key); }

  // Required when `fallback` is empty. text() refuses the empty string.
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

namespace detail {

inline FileError at(const std::string& file, const toml::source_region& where,
                    std::string message) {
  FileError e;
  e.file = file;
  e.line = static_cast<int>(where.begin.line);
  e.column = static_cast<int>(where.begin.column);
  e.message = std::move(message);
  return e;
}

}  // namespace detail

inline toml::table parse_toml(std::string_view text, const std::string& source) {
  try {
    return toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    throw ReadError{detail::at(source, e.source(), std::string(e.description()))};
  }
}

inline std::string read_text(const std::string& path) {
  // Controller and condition files are a few kB; a larger file is refused before it can exhaust
  // memory (a device or a FIFO is refused by its kind, unread).
  constexpr std::size_t kMaxBytes = std::size_t{1} << 20;
  std::string text;
  std::string reason;
  if (!support::read_file_bounded(path, kMaxBytes, text, reason))
    throw ReadError{FileError{path, 0, 0, reason}};
  return text;
}

inline void TableReader::fail(const toml::node& node, const std::string& message) const {
  throw ReadError{detail::at(file_, node.source(), message)};
}

inline void TableReader::fail_here(const std::string& message) const {
  throw ReadError{detail::at(file_, table_.source(), message)};
}

inline const toml::node* TableReader::find(std::string_view key, bool optional) {
  used_.emplace(key);
  const toml::node* node = table_.get(key);
  if (node == nullptr && !optional) fail_here("missing key '" + std::string(key) + "'");
  return node;
}

// Reads a double from any numeric node; fails on NaN and (unless allowed) on infinities.
inline double number_of(const TableReader& where, const toml::node& node, const std::string& what,
                        bool allow_infinite = false) {
  double v = 0.0;
  if (const auto* f = node.as_floating_point()) {
    v = f->get();
  } else if (const auto* i = node.as_integer()) {
    v = static_cast<double>(i->get());
  } else {
    where.fail(node, what + " must be a number");
  }
  if (std::isnan(v)) where.fail(node, what + " must not be NaN");
  if (!allow_infinite && !std::isfinite(v)) where.fail(node, what + " must be finite");
  return v;
}

inline double TableReader::number(std::string_view key, std::optional<double> fallback,
                                  bool allow_infinite) {
  const toml::node* node = find(key, fallback.has_value());
  if (node == nullptr) return *fallback;
  return number_of(*this, *node, "'" + std::string(key) + "'", allow_infinite);
}

inline std::uint64_t TableReader::count(std::string_view key,
                                        std::optional<std::uint64_t> fallback) {
  const toml::node* node = find(key, fallback.has_value());
  if (node == nullptr) return *fallback;
  const auto* i = node->as_integer();
  if (i == nullptr || i->get() < 0)
    fail(*node, "'" + std::string(key) + "' must be a non-negative integer");
  return static_cast<std::uint64_t>(i->get());
}

inline std::string TableReader::text(std::string_view key, std::optional<std::string> fallback) {
  const toml::node* node = find(key, fallback.has_value());
  if (node == nullptr) return *fallback;
  const auto* s = node->as_string();
  if (s == nullptr) fail(*node, "'" + std::string(key) + "' must be a string");
  // "" never stands for the default (`urdf = ""` would silently load the bundled robot).
  if (s->get().empty())
    fail(*node, "'" + std::string(key) + "' is empty" +
                    (fallback ? " (omit the key for its default)" : ": it must name something"));
  return s->get();
}

inline bool TableReader::flag(std::string_view key, std::optional<bool> fallback) {
  const toml::node* node = find(key, fallback.has_value());
  if (node == nullptr) return *fallback;
  const auto* b = node->as_boolean();
  if (b == nullptr) fail(*node, "'" + std::string(key) + "' must be true or false");
  return b->get();
}

inline std::array<double, 3> TableReader::triple(std::string_view key,
                                                 std::optional<std::array<double, 3>> fallback,
                                                 bool allow_infinite) {
  const toml::node* node = find(key, fallback.has_value());
  if (node == nullptr) return *fallback;
  const auto* a = node->as_array();
  if (a == nullptr || a->size() != 3)
    fail(*node, "'" + std::string(key) + "' must be an array of three numbers");
  std::array<double, 3> out{};
  for (std::size_t k = 0; k < 3; ++k)
    out[k] = number_of(*this, *a->get(k), "'" + std::string(key) + "[" + std::to_string(k) + "]'",
                       allow_infinite);
  return out;
}

inline std::optional<TableReader> TableReader::table(std::string_view key, bool required) {
  const toml::node* node = find(key, !required);
  if (node == nullptr) return std::nullopt;
  const auto* t = node->as_table();
  if (t == nullptr) fail(*node, "'" + std::string(key) + "' must be a table");
  return TableReader(*t, file_);
}

inline const toml::array* TableReader::array(std::string_view key, bool required) {
  const toml::node* node = find(key, !required);
  if (node == nullptr) return nullptr;
  const auto* a = node->as_array();
  if (a == nullptr) fail(*node, "'" + std::string(key) + "' must be an array");
  return a;
}

inline void TableReader::finish() const {
  for (auto&& [key, node] : table_) {
    if (used_.count(key.str()) == 0) {
      throw ReadError{
          detail::at(file_, key.source(), "unknown key '" + std::string(key.str()) + "'")};
    }
  }
}

}  // namespace fuzzypid::support
