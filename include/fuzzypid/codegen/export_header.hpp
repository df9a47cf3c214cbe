// A controller file as a self-contained C++ header of constexpr configuration, so that an
// embedded build needs no TOML parser (`fuzzypid export-header`). The values are the continuous
// SI configuration the library builds from the file (joint_controllers.hpp), written as exact
// hexadecimal literals: the header's double controller equals the file's bit for bit.
#pragma once

#include <string>

#include "fuzzypid/controller/controller_spec.hpp"

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

// The header's text. `ns`: the namespace of the generated code (check_namespace() must accept
// it); `source`: named in the header's comment.
[[nodiscard]] std::string export_header(const controller::ControllerSpec& spec,
                                        const std::string& ns, const std::string& source);

}  // namespace fuzzypid::codegen
