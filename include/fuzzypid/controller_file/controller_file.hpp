// Controller files: one controller::ControllerSpec as TOML (docs/tuning.md).
//
// load() reads a file with `file:line:column` errors (parsed by toml++, which stays private to
// this part); to_toml() writes it back so that loading the text gives the same ControllerSpec and
// writing that gives the same text (numbers at %.17g). A rule file the controller names is loaded
// with fuzzypid::rulefile, relative to the controller file's folder.
//
// Library fuzzypid::controller_file (set-up code: it allocates and reports errors).
#pragma once

#include <string>
#include <string_view>

#include "fuzzypid/controller/controller_spec.hpp"
#include "fuzzypid/file_error.hpp"

namespace fuzzypid::controller_file {

using controller::ControllerSpec;

[[nodiscard]] bool parse(std::string_view text, const std::string& source, ControllerSpec& spec,
                         FileError& error);
[[nodiscard]] bool load(const std::string& path, ControllerSpec& spec, FileError& error);
// The file's text; the tools write it through their one output writer (apps/common/output_files).
[[nodiscard]] std::string to_toml(const ControllerSpec& spec);

// 64-bit FNV-1a of a file's bytes as 16 hex digits (controller::TrainedOn); empty when the file
// cannot be read.
[[nodiscard]] std::string file_hash(const std::string& path);

}  // namespace fuzzypid::controller_file
