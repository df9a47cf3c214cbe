// Result codes of the per-tick calls. The control path never throws: every call that can meet bad
// input returns a Status, and a fault leaves the object's state exactly as it was. The type is
// [[nodiscard]]: a Status that is dropped without `(void)` is a warning.
#pragma once

#include <cstdint>

namespace fuzzypid {

enum class [[nodiscard]] Status : std::uint8_t{
    Ok = 0,
    // Informational: the call succeeded but something is worth knowing.
    NoRuleFired,  // no rule had a non-zero firing strength; the outputs are 0
    // Faults: the call changed nothing and the last output is held.
    NonFiniteInput,   // a NaN or infinite input
    InvalidTimeStep,  // dt is not a finite positive number
    InvalidConfig,    // a configuration failed validation
    NumericOverflow,  // finite inputs produced a non-finite result (e.g. huge gains x huge error)
};

// True for the faults, false for Ok and the informational codes.
[[nodiscard]] constexpr bool is_fault(Status s) noexcept {
  return s >= Status::NonFiniteInput;
}

[[nodiscard]] constexpr const char* to_string(Status s) noexcept {
  switch (s) {
    case Status::Ok:
      return "ok";
    case Status::NoRuleFired:
      return "no_rule_fired";
    case Status::NonFiniteInput:
      return "non_finite_input";
    case Status::InvalidTimeStep:
      return "invalid_time_step";
    case Status::InvalidConfig:
      return "invalid_config";
    case Status::NumericOverflow:
      return "numeric_overflow";
  }
  return "unknown";
}

// The more severe of two statuses (faults outrank notes, notes outrank Ok); used to fold per-joint
// results into one.
[[nodiscard]] constexpr Status worst(Status a, Status b) noexcept {
  return a >= b ? a : b;
}

}  // namespace fuzzypid
