// The contract of an output path (output_files.hpp): what may be written where.
#include "output_files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "output_shared.hpp"

namespace fuzzypid::cli {

namespace fs = std::filesystem;
using detail::errno_text;
using detail::in_quotes;
using detail::kind_of;
using detail::resolve_output;

namespace {

// The folder `dir` must exist, be a folder and be writable by this process; a folder whose mode
// grants write permission to no one is treated as read-only even for root.
std::string check_folder(const std::string& dir, const std::string& what) {
  struct stat st {};
  if (::stat(dir.c_str(), &st) != 0)
    return what + ": the folder " + in_quotes(dir) + ": " + errno_text(errno);
  if (!S_ISDIR(st.st_mode)) return what + ": " + in_quotes(dir) + " is not a folder";
  if (::faccessat(AT_FDCWD, dir.c_str(), W_OK | X_OK, AT_EACCESS) != 0)
    return what + ": cannot write into the folder " + in_quotes(dir) + ": " + errno_text(errno);
  if ((st.st_mode & 0222) == 0)
    return what + ": the folder " + in_quotes(dir) + " is read-only (mode " + [&] {
      char b[8];
      std::snprintf(b, sizeof b, "%04o", static_cast<unsigned>(st.st_mode & 07777));
      return std::string(b);
    }() + ")";
  return {};
}

}  // namespace

namespace detail {

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

std::string resolve_output(const std::string& path, std::string& target, bool& exists,
                           struct stat& st) {
  if (path.empty()) return "'' is not a file name";
  const fs::path p(path);
  const std::string name = p.filename().string();
  if (name.empty() || name == "." || name == "..")
    return in_quotes(path) + " is not a file name (it names a folder)";
  target = path;
  exists = false;
  struct stat lst {};
  if (::lstat(path.c_str(), &lst) != 0) {
    const int err = errno;
    if (err != ENOENT) return in_quotes(path) + ": " + errno_text(err);
    const std::string dir = p.has_parent_path() ? p.parent_path().string() : ".";
    return check_folder(dir, in_quotes(path));
  }
  if (S_ISLNK(lst.st_mode)) {
    char* resolved = ::realpath(path.c_str(), nullptr);
    if (resolved == nullptr)
      return in_quotes(path) +
             " is a symbolic link to a missing file or folder: " + errno_text(errno);
    target = resolved;
    std::free(resolved);
    if (::stat(target.c_str(), &lst) != 0) return in_quotes(path) + ": " + errno_text(errno);
  }
  exists = true;
  st = lst;
  const std::string via = target == path ? "" : " (through the link to " + in_quotes(target) + ")";
  if (!S_ISREG(st.st_mode))
    return in_quotes(path) + via + " is " + kind_of(st.st_mode) +
           ": outputs are written only to regular files, never through or over anything else";
  if ((st.st_mode & 0222) == 0)
    return in_quotes(path) + via + " is read-only: make it writable or choose another name";
  const fs::path t(target);
  return check_folder(t.has_parent_path() ? t.parent_path().string() : ".", in_quotes(path));
}

}  // namespace detail

std::string check_output_path(const std::string& path, const std::vector<std::string>& inputs) {
  std::string target;
  bool exists = false;
  struct stat st {};
  if (std::string bad = resolve_output(path, target, exists, st); !bad.empty()) return bad;
  if (!exists) return {};  // a file that does not exist yet is no input
  // Replacing the file that standard output or error goes to (`--csv log > log`, a link to
  // /dev/stdout) would send the tool's own messages into a deleted file.
  for (const int fd : {STDOUT_FILENO, STDERR_FILENO}) {
    struct stat stream {};
    if (::fstat(fd, &stream) == 0 && stream.st_dev == st.st_dev && stream.st_ino == st.st_ino)
      return in_quotes(path) + " is the file the tool's standard " +
             (fd == STDOUT_FILENO ? "output" : "error") + " goes to";
  }
  for (const std::string& input : inputs) {
    struct stat in {};
    if (input.empty() || ::stat(input.c_str(), &in) != 0) continue;
    if (in.st_dev == st.st_dev && in.st_ino == st.st_ino)
      return in_quotes(path) + " is the same file as the input " + in_quotes(input) +
             ": writing it would destroy the input";
  }
  return {};
}

std::string check_output_dir(const std::string& dir, const std::vector<std::string>& names,
                             const std::vector<std::string>& inputs) {
  if (dir.empty()) return "'' is not a folder name";
  struct stat st {};
  if (::stat(dir.c_str(), &st) == 0) {
    if (!S_ISDIR(st.st_mode))
      return in_quotes(dir) + " is " + kind_of(st.st_mode) + ", not an output folder";
    for (const std::string& input : inputs) {
      struct stat in {};
      if (input.empty() || ::stat(input.c_str(), &in) != 0) continue;
      for (const std::string& name : names) {
        struct stat out {};
        const std::string file = (fs::path(dir) / name).string();
        if (::stat(file.c_str(), &out) == 0 && out.st_dev == in.st_dev && out.st_ino == in.st_ino)
          return in_quotes(file) + " is the same file as the input " + in_quotes(input) +
                 ": writing the folder would destroy the input";
      }
    }
  } else if (errno != ENOENT) {
    return in_quotes(dir) + ": " + errno_text(errno);
  }
  // The folder is replaced (or created) by a rename in its parent: the nearest existing ancestor
  // must be a writable folder.
  std::error_code ec;
  fs::path p = fs::absolute(fs::path(dir), ec).lexically_normal();
  if (ec) return in_quotes(dir) + ": " + ec.message();
  if (!p.has_filename()) p = p.parent_path();
  for (fs::path a = p.parent_path();; a = a.parent_path()) {
    struct stat ast {};
    if (::stat(a.c_str(), &ast) == 0) return check_folder(a.string(), in_quotes(dir));
    if (errno != ENOENT) return in_quotes(dir) + ": " + a.string() + ": " + errno_text(errno);
    if (a == a.root_path() || a.empty()) return in_quotes(dir) + ": no existing parent folder";
  }
}

std::string path_from_folder_of(const std::string& out, const std::string& file) {
  // The folder of `p`, absolute with its links resolved; false when it cannot be resolved.
  const auto folder_of = [](const fs::path& p, fs::path& folder) {
    std::error_code ec;
    folder = fs::absolute(p.has_parent_path() ? p.parent_path() : fs::path("."), ec);
    if (!ec) folder = fs::weakly_canonical(folder, ec);
    return !ec;
  };
  const fs::path f(file);
  fs::path from, folder;
  std::error_code ec;
  if (!folder_of(f, from) || !folder_of(fs::path(out), folder))
    return fs::absolute(f, ec).lexically_normal().generic_string();
  const fs::path target = from / f.filename();
  const fs::path relative = target.lexically_relative(folder);
  return relative.empty() ? target.generic_string() : relative.generic_string();
}

}  // namespace fuzzypid::cli
