// Controller files (docs/tuning.md): a controller::ControllerSpec as TOML, with the records a file
// keeps beside it: how the tuner found it ([tuning], tune::Tuning) and what certify found
// ([margins], controller::MarginRecord).
//
// load() reads a file with `file:line:column` errors (parsed by toml++, which stays private to
// this part); to_toml() writes it back so that loading the text gives the same ControllerFile and
// writing that gives the same text (numbers at %.17g). A rule file the controller names is loaded
// with fuzzypid::rulefile, relative to the controller file's folder.
//
// Library fuzzypid::controller_file (set-up code: it allocates and reports errors).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fuzzypid/controller/controller_spec.hpp"
#include "fuzzypid/controller/margin_record.hpp"
#include "fuzzypid/file_error.hpp"
#include "fuzzypid/tune/record.hpp"

namespace fuzzypid::controller_file {

using controller::ControllerSpec;

struct ControllerFile {
  ControllerSpec controller;
  std::optional<tune::Tuning> tuning;               // [tuning]: absent in a file written by hand
  std::optional<controller::MarginRecord> margins;  // [margins]
};

[[nodiscard]] bool parse(std::string_view text, const std::string& source, ControllerFile& file,
                         FileError& error);
[[nodiscard]] bool load(const std::string& path, ControllerFile& file, FileError& error);
// The controller alone, for a reader that runs it: the records are read (and checked) and dropped.
[[nodiscard]] bool parse(std::string_view text, const std::string& source, ControllerSpec& spec,
                         FileError& error);
[[nodiscard]] bool load(const std::string& path, ControllerSpec& spec, FileError& error);
// The file's text; the tools write it through their one output writer (apps/common/output_files).
[[nodiscard]] std::string to_toml(const ControllerFile& file);
// A file of the controller alone (no [tuning], no [margins]: as written by hand).
[[nodiscard]] std::string to_toml(const ControllerSpec& spec);

// 64-bit FNV-1a of a file's bytes as 16 hex digits (tune::TrainedOn); empty when the file
// cannot be read.
[[nodiscard]] std::string file_hash(const std::string& path);

// Whether a controller runs on the robot and path it was tuned on: one line per difference between
// its tuning record (`tuning`, trained_on) and the run, naming the files and their hashes; empty
// when they agree or the controller has no [tuning] (`tuning` null: written by hand). Files are compared by content
// (file_hash), so a copy elsewhere agrees and an edited file in the same place does not. A record
// without a "urdf" entry means the bundled ER50-C20 (`bundled_urdf`), without a "path" entry the
// built-in line A -> B. `controller_path` is the file the record was read from: relative names in
// trained_on are resolved against its folder. `urdf` is the URDF the run loads, `path` its path
// file ("" for the built-in line).
[[nodiscard]] std::vector<std::string> trained_on_differences(const tune::Tuning* tuning,
                                                              const std::string& controller_path,
                                                              const std::string& urdf,
                                                              const std::string& path,
                                                              const std::string& bundled_urdf);
// Whether `conditions` (a condition file a run reads) is the one the tuning record names (its
// "conditions" entry of trained_on, resolved against the folder of `controller_path`) but no
// longer has the content the tune read: then a line naming both hashes, else empty (another
// condition file, the same content, or no record). The training set's own results, and any
// comparison on its held-out set, hold only for the content the tune read.
[[nodiscard]] std::string conditions_changed(const tune::Tuning* tuning,
                                             const std::string& controller_path,
                                             const std::string& conditions);

}  // namespace fuzzypid::controller_file
