// Reading a whole input file with a size bound: the one reader of every outside input (URDF, path
// CSV, rule files, controller and condition files). Standard library and POSIX only: no dependency
// on any part of the project, so every part may include it privately (it is not a public header and
// is never installed).
//
// Only regular files are read. A FIFO, a device, a socket or a folder is refused by its kind before
// it is opened (stat), so a FIFO with no writer cannot block the tool and /dev/zero cannot feed it
// forever; the file is then opened with O_NONBLOCK and checked again (fstat), so a regular file
// swapped for a FIFO between the two calls is refused too instead of blocking. A regular file
// larger than the bound is refused after reading at most max_bytes + 1 bytes.
#pragma once

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <cstring>
#include <string>

namespace fuzzypid::support {

// "a FIFO", "a folder", ... for a file that is not a regular file.
inline const char* file_kind(mode_t mode) noexcept {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Opens `path` for reading when it is a regular file (a symbolic link is followed). Returns the
// descriptor (close-on-exec), or -1 with the reason in `error`: "cannot open 'P': <strerror>" or
// "'P' is a FIFO, not a regular file" (a directory, a character device, ...). Never blocks.
[[nodiscard]] inline int open_regular_file(const std::string& path, std::string& error) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    error = "cannot open '" + path + "': " + std::strerror(errno);
    return -1;
  }
  if (!S_ISREG(st.st_mode)) {
    error = "'" + path + "' is " + file_kind(st.st_mode) + ", not a regular file";
    return -1;
  }
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) {
    error = "cannot open '" + path + "': " + std::strerror(errno);
    return -1;
  }
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    const int err = errno;
    ::close(fd);
    error = S_ISREG(st.st_mode)
                ? "cannot open '" + path + "': " + std::strerror(err)
                : "'" + path + "' is " + file_kind(st.st_mode) + ", not a regular file";
    return -1;
  }
  return fd;
}

// Reads `path` into `out`. Returns false with a reason in `error` (open_regular_file's, "... is
// larger than N bytes", "cannot read ...") when the file cannot be read whole within max_bytes.
// Never throws other than std::bad_alloc.
[[nodiscard]] inline bool read_file_bounded(const std::string& path, std::size_t max_bytes,
                                            std::string& out, std::string& error) {
  out.clear();
  const int fd = open_regular_file(path, error);
  if (fd < 0) return false;
  const auto too_large = [&] {
    ::close(fd);
    out.clear();
    error = "'" + path + "' is larger than " + std::to_string(max_bytes) + " bytes";
    return false;
  };
  struct stat st {};
  if (::fstat(fd, &st) == 0 && static_cast<unsigned long long>(st.st_size) > max_bytes)
    return too_large();
  char buffer[64 * 1024];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      ::close(fd);
      out.clear();
      error = "cannot read '" + path + "': " + std::strerror(err);
      return false;
    }
    if (n == 0) break;
    if (out.size() + static_cast<std::size_t>(n) > max_bytes) return too_large();
    out.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fd);
  return true;
}

}  // namespace fuzzypid::support
