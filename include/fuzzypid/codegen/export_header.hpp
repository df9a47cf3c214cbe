// A controller file as a self-contained C++ header of constexpr configuration, so that an
// embedded build needs no TOML parser (`fuzzypid export-header`). The values are the continuous
// SI configuration the library builds from the file (joint_controllers.hpp), written as exact
// hexadecimal literals: the header's double controller equals the file's bit for bit.
#pragma once

#include <array>
#include <string>

#include "fuzzypid/controller/controller_spec.hpp"
#include "fuzzypid/controller/margin_record.hpp"

namespace fuzzypid::codegen {

// "" when `ns` can name the generated code's namespace, else why not. Accepted: one C++ identifier,
// or several joined by `::` (a nested namespace, C++17), each of letters, digits and `_` not
// starting with a digit, and none of: a C++ keyword or alternative token (`class`, `and`, ...,
// up to C++20's), `final`/`override`/`import`/`module`, a reserved name (containing `__`,
// starting with `_` and a capital, or with `_` at global scope, i.e. in the first part), `std`,
// `posix`, `main`, `fuzzypid` (the generated code names `std::` and `fuzzypid::` from inside the
// namespace), a name in capitals only (left to macros), or a macro of the C and POSIX headers or
// of GNU mode (`errno`, `NULL`, `linux`, `unix`, ...). Every accepted name compiles.
[[nodiscard]] std::string check_namespace(const std::string& ns);

// "" when every value the header writes is finite after conversion to float (the embedded
// controller's Scalar), else the first that is not: a finite double beyond FLT_MAX (kp = 1e39)
// would silently become an infinite float gain. Infinite values of the file (open bounds) stay
// infinite and are accepted.
[[nodiscard]] std::string check_float_range(const controller::ControllerSpec& spec);

// The plant a controller's command was simulated on, so that a drive applying the header's
// command gets the simulated torque: tau_i = J^_i u_i (acceleration gains) clamped to
// |tau_i| <= torque_limit_nm[i].
struct PlantRecord {
  std::string robot;  // what it was: URDF, path and tick, for the comment
  std::array<double, 6> nominal_inertia_kgm2{};  // J^_i at the path's start (sim::Experiment)
  std::array<double, 6> torque_limit_nm{};       // the simulation's clamp (+inf: none)
};

// The header's text. `ns`: the namespace of the generated code (check_namespace() must accept
// it); `source`: named in the header's comment; `plant`, when given, adds kNominalInertiaKgm2,
// kTorqueLimitNm and kOutputLimit (the limit in the controller's output units); `margins`, when
// given, adds the stability margins and certificate (sim::certify) with its assumptions:
// kGainMarginDb, kPhaseMarginDeg, kDelayMarginMs, kDiskMargin (per joint, worst case over the
// conditions named), kCertified and kCertificate.
[[nodiscard]] std::string export_header(const controller::ControllerSpec& spec,
                                        const std::string& ns, const std::string& source,
                                        const PlantRecord* plant = nullptr,
                                        const controller::MarginRecord* margins = nullptr);

}  // namespace fuzzypid::codegen
