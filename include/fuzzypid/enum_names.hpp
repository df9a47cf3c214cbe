// Enumerations named by one table each: the same table parses a name, prints a value and lists
// the accepted names in messages and --help, so a name cannot be accepted in one place and
// printed differently in another.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace fuzzypid {

template <class Enum>
struct EnumName {
  Enum value;
  const char* name;
};

template <class Enum, std::size_t N>
[[nodiscard]] constexpr const char* name_of(const std::array<EnumName<Enum>, N>& table,
                                            Enum value) noexcept {
  for (const auto& e : table)
    if (e.value == value) return e.name;
  return "unknown";
}

template <class Enum, std::size_t N>
[[nodiscard]] std::optional<Enum> parse_enum(const std::array<EnumName<Enum>, N>& table,
                                             std::string_view text) noexcept {
  for (const auto& e : table)
    if (text == e.name) return e.value;
  return std::nullopt;
}

// "a|b|c": the accepted names, for messages and --help.
template <class Enum, std::size_t N>
[[nodiscard]] std::string names_of(const std::array<EnumName<Enum>, N>& table) {
  std::string out;
  for (const auto& e : table) {
    if (!out.empty()) out += '|';
    out += e.name;
  }
  return out;
}

}  // namespace fuzzypid
