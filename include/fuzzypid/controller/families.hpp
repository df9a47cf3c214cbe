// The list of controller families, and what is generated from it: the traits and name tables,
// a family's position (family_of), dispatch of set-up code on a family (with_family) and the
// runtime variant JointControllers holds.
//
// Adding a family: its file in families/ (traits, validate, configure, header_code, build; see
// pid.hpp for the shape; set-up code that is not a template may go beside it in
// src/controller/families/) and its supervisor in supervisor/, then its entry in FamilyList below.
// Nothing else names it. A build can add one more family without editing this file: with
// FUZZYPID_EXTRA_FAMILY_HEADER defined as its file (a quoted header name) and
// FUZZYPID_EXTRA_FAMILY as its type, it comes last in the list (tests/controller/ does so).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <variant>

#include "fuzzypid/controller/family.hpp"
#include "fuzzypid/enum_names.hpp"

namespace fuzzypid::controller {

template <class... Families>
struct FamilyTypes {};

}  // namespace fuzzypid::controller

#include "fuzzypid/controller/families/fuzzy.hpp"
#include "fuzzypid/controller/families/fuzzy_rules.hpp"
#include "fuzzypid/controller/families/pid.hpp"
#include "fuzzypid/controller/families/scheduled.hpp"
#ifdef FUZZYPID_EXTRA_FAMILY_HEADER
#include FUZZYPID_EXTRA_FAMILY_HEADER
#endif

namespace fuzzypid::controller {
// The first is the default family (Family{}).
using FamilyList =
    FamilyTypes<families::Pid, families::Scheduled, families::Fuzzy, families::FuzzyRules
#ifdef FUZZYPID_EXTRA_FAMILY
                ,
                FUZZYPID_EXTRA_FAMILY
#endif
                >;
}  // namespace fuzzypid::controller

namespace fuzzypid::controller {

namespace detail {

template <class T, class... Ts>
inline constexpr bool kContains = (std::is_same_v<T, Ts> || ...);

// A variant of the distinct types of Ts, in first-seen order (two families may share a runtime).
template <class Variant, class... Ts>
struct Distinct;
template <class... Seen>
struct Distinct<std::variant<Seen...>> {
  using Type = std::variant<Seen...>;
};
template <class... Seen, class T, class... Rest>
struct Distinct<std::variant<Seen...>, T, Rest...> {
  using Type =
      typename std::conditional_t<kContains<T, Seen...>, Distinct<std::variant<Seen...>, Rest...>,
                                  Distinct<std::variant<Seen..., T>, Rest...>>::Type;
};

template <class Tuple>
struct RuntimeVariant;
template <class... Ts>
struct RuntimeVariant<std::tuple<Ts...>> {
  using Type = typename Distinct<std::variant<>, Ts...>::Type;
};

template <class List>
struct FamilyTable;
template <class... Families>
struct FamilyTable<FamilyTypes<Families...>> {
  static constexpr std::size_t kSize = sizeof...(Families);
  static_assert(kSize >= 1 && kSize <= 255, "one to 255 families");

  static constexpr std::array<FamilyTraits, kSize> kTraits{{Families::kTraits...}};

  using Runtime = typename RuntimeVariant<decltype(std::tuple_cat(
      std::declval<typename Families::Runtimes>()...))>::Type;

  template <class F>
  static constexpr std::size_t index_of() noexcept {
    constexpr std::array<bool, kSize> match{{std::is_same_v<F, Families>...}};
    for (std::size_t k = 0; k < kSize; ++k)
      if (match[k]) return k;
    return kSize;
  }

  // fn(F{}) for the family F at `family`'s position; `fallback` when there is none.
  template <class Result, class Fn>
  static Result with(Family family, Fn&& fn, Result fallback) {
    return with_impl<Result>(family, fn, std::move(fallback),
                             std::index_sequence_for<Families...>{});
  }

 private:
  template <class Result, class Fn, std::size_t... I>
  static Result with_impl(Family family, Fn& fn, Result fallback, std::index_sequence<I...>) {
    std::optional<Result> result;
    (void)((family.index() == I ? (result.emplace(fn(Families{})), true) : false) || ...);
    return result ? std::move(*result) : std::move(fallback);
  }
};

template <class... Families>
constexpr std::array<EnumName<Family>, sizeof...(Families)> family_names(
    FamilyTypes<Families...> /*list*/) noexcept {
  std::array<EnumName<Family>, sizeof...(Families)> out{};
  std::uint8_t k = 0;
  ((out[k] = {Family(k), Families::kTraits.name}, ++k), ...);
  return out;
}

}  // namespace detail

using FamilyTable = detail::FamilyTable<FamilyList>;

// Every family's traits, in the list's order.
inline constexpr const std::array<FamilyTraits, FamilyTable::kSize>& kFamilies =
    FamilyTable::kTraits;
// The names of every family, for parse_enum, names_of and controller files.
inline constexpr std::array<EnumName<Family>, FamilyTable::kSize> kFamilyNames =
    detail::family_names(FamilyList{});

// The family F of the list.
template <class F>
[[nodiscard]] constexpr Family family_of() noexcept {
  constexpr std::size_t k = FamilyTable::index_of<F>();
  static_assert(k < FamilyTable::kSize, "F is not in FamilyList");
  return Family(static_cast<std::uint8_t>(k));
}

// A family's traits (the first family's for a position outside the list).
[[nodiscard]] constexpr const FamilyTraits& family_traits(Family f) noexcept {
  return f.index() < kFamilies.size() ? kFamilies[f.index()] : kFamilies[0];
}

// The family a controller file or command line names `name`; nullopt for none.
[[nodiscard]] inline std::optional<Family> parse_family(std::string_view name) noexcept {
  return parse_enum(kFamilyNames, name);
}

[[nodiscard]] constexpr const char* to_string(Family f) noexcept {
  return f.index() < kFamilies.size() ? kFamilies[f.index()].name : "unknown";
}

// Set-up code for one family without naming it: fn(F{}) with F the family type at `family`'s
// position, or `fallback` when there is none.
template <class Result, class Fn>
[[nodiscard]] Result with_family(Family family, Fn&& fn, Result fallback) {
  return FamilyTable::with<Result>(family, fn, std::move(fallback));
}

}  // namespace fuzzypid::controller
