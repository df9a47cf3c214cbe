#include "fuzzypid/controller_file/toml_reader.hpp"
#include "fuzzypid_support/bounded_read.hpp"

#include <cmath>

namespace fuzzypid::controller_file {

namespace {

Error at(const std::string& file, const toml::source_region& where, std::string message) {
  Error e;
  e.file = file;
  e.line = static_cast<int>(where.begin.line);
  e.column = static_cast<int>(where.begin.column);
  e.message = std::move(message);
  return e;
}

}  // namespace

std::string Error::to_string() const {
  if (line <= 0) return file + ": " + message;
  return file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + message;
}

toml::table parse_toml(std::string_view text, const std::string& source) {
  try {
    return toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    throw ReadError{at(source, e.source(), std::string(e.description()))};
  }
}

std::string read_text(const std::string& path) {
  // Controller and condition files are a few kB; a larger file, or a device that never ends
  // (/dev/zero), is refused before it can exhaust memory.
  constexpr std::size_t kMaxBytes = std::size_t{1} << 20;
  std::string text;
  std::string reason;
  if (!support::read_file_bounded(path, kMaxBytes, text, reason))
    throw ReadError{Error{path, 0, 0, reason}};
  return text;
}

void TableReader::fail(const toml::node& node, const std::string& message) const {
  throw ReadError{at(file_, node.source(), message)};
}

void TableReader::fail_here(const std::string& message) const {
  throw ReadError{at(file_, table_.source(), message)};
}

const toml::node* TableReader::find(std::string_view key, bool optional) {
  used_.emplace(key);
  const toml::node* node = table_.get(key);
  if (node == nullptr && !optional) fail_here("missing key '" + std::string(key) + "'");
  return node;
}

double number_of(const TableReader& where, const toml::node& node, const std::string& what,
                 bool allow_infinite) {
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

double TableReader::number(std::string_view key, std::optional<double> fallback,
                           bool allow_infinite) {
  const toml::node* node = find(key, fallback.has_value());
  if (node == nullptr) return *fallback;
  return number_of(*this, *node, "'" + std::string(key) + "'", allow_infinite);
}

std::uint64_t TableReader::count(std::string_view key, std::optional<std::uint64_t> fallback) {
  const toml::node* node = find(key, fallback.has_value());
  if (node == nullptr) return *fallback;
  const auto* i = node->as_integer();
  if (i == nullptr || i->get() < 0)
    fail(*node, "'" + std::string(key) + "' must be a non-negative integer");
  return static_cast<std::uint64_t>(i->get());
}

std::string TableReader::text(std::string_view key, std::optional<std::string> fallback) {
  const toml::node* node = find(key, fallback.has_value());
  if (node == nullptr) return *fallback;
  const auto* s = node->as_string();
  if (s == nullptr) fail(*node, "'" + std::string(key) + "' must be a string");
  return s->get();
}

bool TableReader::flag(std::string_view key, std::optional<bool> fallback) {
  const toml::node* node = find(key, fallback.has_value());
  if (node == nullptr) return *fallback;
  const auto* b = node->as_boolean();
  if (b == nullptr) fail(*node, "'" + std::string(key) + "' must be true or false");
  return b->get();
}

std::array<double, 3> TableReader::triple(std::string_view key,
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

std::optional<TableReader> TableReader::table(std::string_view key, bool required) {
  const toml::node* node = find(key, !required);
  if (node == nullptr) return std::nullopt;
  const auto* t = node->as_table();
  if (t == nullptr) fail(*node, "'" + std::string(key) + "' must be a table");
  return TableReader(*t, file_);
}

const toml::array* TableReader::array(std::string_view key, bool required) {
  const toml::node* node = find(key, !required);
  if (node == nullptr) return nullptr;
  const auto* a = node->as_array();
  if (a == nullptr) fail(*node, "'" + std::string(key) + "' must be an array");
  return a;
}

void TableReader::finish() const {
  for (auto&& [key, node] : table_) {
    if (used_.count(key.str()) == 0) {
      throw ReadError{at(file_, key.source(), "unknown key '" + std::string(key.str()) + "'")};
    }
  }
}

}  // namespace fuzzypid::controller_file
