// A controller family's identity and what consumers may ask of it without naming it.
//
// A family is one file in controller/families/ (its traits, checks, configuration and runtime)
// plus its supervisor in supervisor/, and one entry in families.hpp's list. Code outside those files
// asks a family's traits (is it supervised, what does output_scale hold, does it read a rule base
// or a rule table) instead of comparing it with a name, so a new family that answers the same
// questions needs no change elsewhere.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace fuzzypid::controller {

// A family: its position in families.hpp's list. The default is the list's first family, the
// fixed PID. Names, traits and parsing: families.hpp (family_traits, kFamilyNames).
class Family {
 public:
  constexpr Family() noexcept = default;
  constexpr explicit Family(std::uint8_t index) noexcept : index_(index) {}

  [[nodiscard]] constexpr std::size_t index() const noexcept { return index_; }

 private:
  std::uint8_t index_ = 0;
};

[[nodiscard]] constexpr bool operator==(Family a, Family b) noexcept {
  return a.index() == b.index();
}
[[nodiscard]] constexpr bool operator!=(Family a, Family b) noexcept {
  return a.index() != b.index();
}

// What a family's ControllerSpec::supervisor.output_scale holds.
enum class OutputScale : std::uint8_t {
  None,    // no supervisor: the gains are fixed
  Scales,  // S (Sp, Si, Sd) in gain units per supervisor unit: K = K0 + S dK (Eq. 6)
  Ratios,  // R (Rp, Ri, Rd) > 0, the large-error gain ratios of a schedule: K -> K0 R
};

struct FamilyTraits {
  const char* name;     // in controller files and on command lines
  const char* summary;  // one line for --help and docs
  OutputScale output_scale = OutputScale::None;
  // Reads supervisor.rule_base, conjunction, gain_update and rule_file (a fuzzy rule base).
  bool rule_base = false;
  // Carries supervisor.rule_table (a tuned 7x7 table per gain over a tunable partition).
  bool rule_table = false;

  // The gains are retuned every tick from (Ke e, Kec ec): error_scale, error_rate_scale,
  // output_scale and the bounds apply.
  [[nodiscard]] constexpr bool supervised() const noexcept {
    return output_scale != OutputScale::None;
  }
};

// What a supervised family adds to an exported header (codegen/export_header.hpp): the includes
// its supervisor needs and, inside the generated namespace, the definitions of
// `Supervisor<Scalar>` (the supervisor type) and `kSupervisor<Scalar>` (the shared, immutable
// instance the joints point to). Empty for a family without a supervisor.
struct SupervisorCode {
  std::string includes;
  std::string definitions;
};

}  // namespace fuzzypid::controller
