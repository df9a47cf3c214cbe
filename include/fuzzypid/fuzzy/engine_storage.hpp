// How an engine model (fuzzy/engine_model.hpp) stores its variables, terms and rules.
//
// The model's template parameter `Cap`, in one of two forms with one evaluation code:
//   EngineCapacity<...>  fixed-capacity arrays (std::array), no heap, constexpr-constructible: for
//                        microcontrollers and generated headers. SmallCapacity is the paper's
//                        shape (2 inputs, 3 outputs, 7 terms, 49 rules); FixedCapacity holds
//                        8 inputs, 8 outputs, 64 terms per variable, 2,048 rules in 8 blocks.
//   SizedCapacity<Limits> arrays allocated once with the exact counts of one model (variables,
//                        terms, coefficients, rules, blocks, antecedent tokens, conclusions, names,
//                        Discrete points, formula steps), bounded by the fixed capacity `Limits`;
//                        copying and make_sized() allocate, evaluation does not. DefaultCapacity,
//                        what the rule-file readers produce, is SizedCapacity<FixedCapacity>.
// A sized model is filled through copy_model() (engine_model_copy.hpp) from a fixed one (readers
// build into a FixedCapacity model, then copy it to the size of the file). Memory:
// docs/rule_files.md.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace fuzzypid::fuzzy {

// An array allocated once with a size given at set-up (SizedCapacity's storage): the indexing of
// std::array over a std::vector that never grows (a copy allocates exactly the same size).
template <class T>
class SizedArray {
 public:
  SizedArray() noexcept = default;
  // Set-up: `n` value-initialised elements (allocates; n = 0 allocates nothing).
  explicit SizedArray(std::size_t n) : items_(n) {}

  T& operator[](std::size_t k) noexcept { return items_[k]; }
  const T& operator[](std::size_t k) const noexcept { return items_[k]; }
  T* data() noexcept { return items_.data(); }
  const T* data() const noexcept { return items_.data(); }
  std::size_t size() const noexcept { return items_.size(); }
  T* begin() noexcept { return data(); }
  T* end() noexcept { return data() + size(); }
  const T* begin() const noexcept { return data(); }
  const T* end() const noexcept { return data() + size(); }

  bool operator==(const SizedArray& other) const { return items_ == other.items_; }
  bool operator!=(const SizedArray& other) const { return !(*this == other); }

 private:
  std::vector<T> items_;
};

// The compile-time capacity of an engine model, stored in fixed-size arrays.
template <std::size_t Inputs, std::size_t Outputs, std::size_t Terms, std::size_t Rules,
          std::size_t Blocks, std::size_t Tokens, std::size_t Conclusions, std::size_t Points,
          std::size_t Steps = 1>
struct EngineCapacity {
  static_assert(Inputs >= 1 && Inputs <= 255 && Outputs >= 1 && Outputs <= 255,
                "inputs and outputs: 1..255");
  static_assert(Terms >= 1 && Terms <= 255, "terms per variable: 1..255");
  static_assert(Rules >= 1 && Blocks >= 1 && Tokens >= 1 && Conclusions >= 1, "empty capacity");
  static constexpr std::size_t inputs = Inputs;
  static constexpr std::size_t outputs = Outputs;
  static constexpr std::size_t terms = Terms;              // per variable
  static constexpr std::size_t rules = Rules;              // in all blocks
  static constexpr std::size_t blocks = Blocks;            // rule blocks
  static constexpr std::size_t tokens = Tokens;            // antecedent tokens of all rules
  static constexpr std::size_t conclusions = Conclusions;  // conclusions of all rules
  static constexpr std::size_t points = Points;            // (x, y) pairs of all Discrete terms
  static constexpr std::size_t steps = Steps;              // formula steps of all Function terms
  static constexpr std::size_t rule_tokens = 63;           // tokens of one antecedent
  static constexpr bool sized = false;
  template <class T, std::size_t N>
  using Array = std::array<T, N>;
};

// Storage sized to one model, within the limits of the fixed capacity `Limits`.
template <class Limits>
struct SizedCapacity : Limits {
  static_assert(!Limits::sized, "the limits of a sized capacity are a fixed capacity");
  using Fixed = Limits;
  // Hides the fixed capacity's `sized` on purpose: the same name tells the two forms apart.
  // cppcheck-suppress duplInheritedMember
  static constexpr bool sized = true;
  template <class T, std::size_t N>
  using Array = SizedArray<T>;
};

using FixedCapacity = EngineCapacity<8, 8, 64, 2048, 8, 16384, 8192, 4096, 4096>;
using DefaultCapacity = SizedCapacity<FixedCapacity>;
using SmallCapacity = EngineCapacity<2, 3, 7, 49, 1, 147, 147, 1>;

// The default capacity under short names.
inline constexpr std::size_t kMaxInputs = DefaultCapacity::inputs;
inline constexpr std::size_t kMaxOutputs = DefaultCapacity::outputs;
inline constexpr std::size_t kMaxNameLength = 31;
inline constexpr std::size_t kMaxHedges = 4;  // per proposition

// A NUL-terminated name of at most kMaxNameLength bytes (any bytes but NUL).
using Name = std::array<char, kMaxNameLength + 1>;

// Copies `length` bytes of `text` into `name`; false (name unchanged) when too long.
inline bool set_name(Name& name, const char* text, std::size_t length) noexcept {
  if (length > kMaxNameLength) return false;
  std::size_t k = 0;
  for (; k < length; ++k)
    name[k] = text[k];
  name[k] = '\0';  // k = length <= kMaxNameLength: the last element at most
  return true;
}

}  // namespace fuzzypid::fuzzy
