// Reading a whole input file with a size bound, for the loaders of outside input (URDF, rule
// files). Standard library and POSIX only: no dependency on any part of the project, so every part
// may include it privately (it is not a public header and is never installed).
//
// A file larger than the bound -- or a device that never ends, such as /dev/zero -- is refused
// after reading at most max_bytes + 1 bytes, instead of growing a string until the allocation
// fails. Directories are refused by name; pipes and other streams are read up to the bound.
#pragma once

#include <cerrno>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <string>

#include <sys/stat.h>

namespace fuzzypid::support {

// Reads `path` into `out`. Returns false with a reason in `error` ("cannot open ...", "... is a
// directory", "... is larger than N bytes", "cannot read ...") when the file cannot be read whole
// within max_bytes. Never throws other than std::bad_alloc for max_bytes itself.
[[nodiscard]] inline bool read_file_bounded(const std::string& path, std::size_t max_bytes,
                                            std::string& out, std::string& error) {
  out.clear();
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) {
    error = "cannot open '" + path + "': " + std::strerror(errno);
    return false;
  }
  struct stat st {};
  if (::fstat(fileno(f), &st) == 0 && S_ISDIR(st.st_mode)) {
    std::fclose(f);
    error = "'" + path + "' is a directory";
    return false;
  }
  if (S_ISREG(st.st_mode) && static_cast<unsigned long long>(st.st_size) > max_bytes) {
    std::fclose(f);
    error = "'" + path + "' is larger than " + std::to_string(max_bytes) + " bytes";
    return false;
  }
  char buffer[64 * 1024];
  for (;;) {
    const std::size_t n = std::fread(buffer, 1, sizeof buffer, f);
    if (out.size() + n > max_bytes) {
      std::fclose(f);
      out.clear();
      error = "'" + path + "' is larger than " + std::to_string(max_bytes) + " bytes";
      return false;
    }
    out.append(buffer, n);
    if (n < sizeof buffer) break;
  }
  const bool failed = std::ferror(f) != 0;
  const int err = errno;
  std::fclose(f);
  if (failed) {
    out.clear();
    error = "cannot read '" + path + "': " + std::strerror(err);
    return false;
  }
  return true;
}

}  // namespace fuzzypid::support
