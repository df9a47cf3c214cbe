// Where a file the tools read is wrong: the error of every set-up loader of the project's text
// files (controller files, condition files), printed as `file:line:column: message`.
#pragma once

#include <string>

namespace fuzzypid {

struct FileError {
  std::string file;
  int line = 0;  // 1-based; 0 when unknown (e.g. the file cannot be read)
  int column = 0;
  std::string message;

  // "file:line:column: message" ("file: message" without a position).
  [[nodiscard]] std::string to_string() const {
    if (line <= 0) return file + ": " + message;
    return file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + message;
  }
};

}  // namespace fuzzypid
