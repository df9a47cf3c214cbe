// A controller file as a self-contained C++ header of constexpr configuration, so that an
// embedded build needs no TOML parser (`fuzzypid export-header`). The values are the continuous
// SI configuration the library builds from the file (joint_controllers.hpp), written as exact
// hexadecimal literals: the header's double controller equals the file's bit for bit.
#pragma once

#include <string>

#include "fuzzypid/controller_file/controller_file.hpp"

namespace fuzzypid::controller_file {

// `ns`: the namespace of the generated code; `source`: named in the header's comment.
[[nodiscard]] std::string export_header(const ControllerSpec& spec, const std::string& ns,
                                        const std::string& source);

}  // namespace fuzzypid::controller_file
