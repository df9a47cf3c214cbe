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
#include <vector>

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

// Whether a controller runs on the robot and path it was tuned on: one line per difference between
// its tuning record (tuning.trained_on) and the run, naming the files and their hashes; empty when
// they agree or the controller has no [tuning] (written by hand). Files are compared by content
// (file_hash), so a copy elsewhere agrees and an edited file in the same place does not. A record
// without a "urdf" entry means the bundled ER50-C20 (`bundled_urdf`), without a "path" entry the
// built-in line A -> B. `controller_path` is the file the spec was read from: relative names in
// trained_on are resolved against its folder. `urdf` is the URDF the run loads, `path` its path
// file ("" for the built-in line).
[[nodiscard]] std::vector<std::string> trained_on_differences(const ControllerSpec& spec,
                                                              const std::string& controller_path,
                                                              const std::string& urdf,
                                                              const std::string& path,
                                                              const std::string& bundled_urdf);

}  // namespace fuzzypid::controller_file
