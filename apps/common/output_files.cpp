// OutputSet and OutputFile (output_files.hpp).
#include "output_files.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace fuzzypid::cli {
namespace {

namespace fs = std::filesystem;

std::string errno_text(int err) {
  return std::strerror(err);
}

// ---------------------------------------------------------------------------------------------
// Clean-up on SIGINT/SIGTERM of the one set being written. The handler only uses
// async-signal-safe calls (unlink, rmdir, signal, raise) on paths prepared before.

constexpr std::size_t kMaxSignalFiles = 16;
char g_signal_files[kMaxSignalFiles][PATH_MAX];
std::size_t g_signal_file_count = 0;
char g_signal_dir[PATH_MAX];
char g_signal_lock[PATH_MAX];
volatile std::sig_atomic_t g_signal_armed = 0;
struct sigaction g_old_int {};
struct sigaction g_old_term {};

extern "C" void remove_on_signal(int sig) {
  if (g_signal_armed != 0) {
    for (std::size_t k = 0; k < g_signal_file_count; ++k)
      ::unlink(g_signal_files[k]);
    ::rmdir(g_signal_dir);
    ::unlink(g_signal_lock);
  }
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

bool copy_path(char (&to)[PATH_MAX], const std::string& from) {
  if (from.size() >= PATH_MAX) return false;
  std::memcpy(to, from.c_str(), from.size() + 1);
  return true;
}

void arm_signal_cleanup(const std::string& dir, const std::vector<std::string>& names,
                        const std::string& lock) {
  g_signal_armed = 0;
  if (names.size() > kMaxSignalFiles || !copy_path(g_signal_dir, dir) ||
      !copy_path(g_signal_lock, lock))
    return;  // left to the next run's clean-up
  for (std::size_t k = 0; k < names.size(); ++k)
    if (!copy_path(g_signal_files[k], dir + "/" + names[k])) return;
  g_signal_file_count = names.size();
  struct sigaction sa {};
  sa.sa_handler = remove_on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, &g_old_int);
  sigaction(SIGTERM, &sa, &g_old_term);
  g_signal_armed = 1;
}

void disarm_signal_cleanup() {
  if (g_signal_armed == 0) return;
  g_signal_armed = 0;
  sigaction(SIGINT, &g_old_int, nullptr);
  sigaction(SIGTERM, &g_old_term, nullptr);
}

// ---------------------------------------------------------------------------------------------

// Takes an exclusive flock on `path` (created if needed) without waiting. Guards against the file
// being unlinked by its previous holder between our open and our flock. Returns the descriptor or
// -1 with `error` set.
int lock_file(const std::string& path, const std::string& what, std::string& error) {
  for (int attempt = 0; attempt < 8; ++attempt) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) {
      error = "cannot create the lock file " + path + ": " + errno_text(errno);
      return -1;
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int err = errno;
      ::close(fd);
      error = err == EWOULDBLOCK ? what + " is being written by another process (lock " + path + ")"
                                 : "cannot lock " + path + ": " + errno_text(err);
      return -1;
    }
    struct stat held {};
    struct stat named {};
    if (::fstat(fd, &held) == 0 && ::stat(path.c_str(), &named) == 0 &&
        held.st_dev == named.st_dev && held.st_ino == named.st_ino)
      return fd;
    ::close(fd);  // the file was replaced while we waited: lock the current one
  }
  error = "cannot lock " + path + ": it keeps being replaced";
  return -1;
}

// True when `dir` is the current directory or one of its ancestors.
bool contains_cwd(const fs::path& dir) {
  std::error_code ec;
  const fs::path cwd = fs::current_path(ec);
  if (ec) return false;
  for (fs::path p = cwd;; p = p.parent_path()) {
    if (fs::equivalent(p, dir, ec)) return true;
    if (p == p.root_path() || p.empty()) return false;
  }
}

bool rename_exchange(const std::string& a, const std::string& b, int& err) {
  if (::renameat2(AT_FDCWD, a.c_str(), AT_FDCWD, b.c_str(), RENAME_EXCHANGE) == 0) return true;
  err = errno;
  return false;
}

}  // namespace

std::unique_ptr<OutputSet> OutputSet::open(const std::string& dir,
                                           const std::vector<std::string>& names,
                                           std::string& error) {
  std::unique_ptr<OutputSet> set(new OutputSet());
  std::error_code ec;
  if (dir.empty()) {
    error = "empty output directory name";
    return nullptr;
  }
  fs::path target = fs::absolute(dir, ec);
  if (!ec) {
    std::error_code missing;  // a target that does not exist yet is fine
    if (fs::is_symlink(fs::symlink_status(target, missing))) target = fs::canonical(target, ec);
  }
  if (ec) {
    error = "cannot resolve the output directory " + dir + ": " + ec.message();
    return nullptr;
  }
  target = target.lexically_normal();
  if (!target.has_filename()) target = target.parent_path();  // "out/" -> "out"
  if (target == target.root_path() || target.filename() == "." || target.filename() == "..") {
    error = "cannot use " + dir + " as an output directory: name a directory of its own";
    return nullptr;
  }
  const fs::path parent = target.parent_path();
  const std::string name = target.filename().string();
  fs::create_directories(parent, ec);
  if (ec) {
    error = "cannot create " + parent.string() + ": " + ec.message();
    return nullptr;
  }
  set->target_ = target.string();
  set->names_ = names;
  set->lock_path_ = (parent / ("." + name + ".lock")).string();
  set->lock_fd_ = lock_file(set->lock_path_, "the output directory " + dir, error);
  if (set->lock_fd_ < 0) return nullptr;

  // The target, when it exists, must be a directory we may replace whole.
  std::error_code missing;
  const fs::file_status st = fs::symlink_status(target, missing);
  if (fs::exists(st)) {
    if (!fs::is_directory(st)) {
      error = "the output path " + dir + " exists and is not a directory";
      return nullptr;
    }
    if (contains_cwd(target)) {
      error = "the output directory " + dir + " contains the current directory";
      return nullptr;
    }
    for (const fs::directory_entry& entry : fs::directory_iterator(target, ec)) {
      if (!entry.is_regular_file(ec) || entry.is_symlink(ec)) {
        error = "the output directory " + dir + " holds '" + entry.path().filename().string() +
                "', which is not a regular file: the directory is replaced as a whole, so name a "
                "new directory or one that holds only files";
        return nullptr;
      }
    }
    if (ec) {
      error = "cannot list " + dir + ": " + ec.message();
      return nullptr;
    }
  }

  // We hold the lock, so every temporary of this target belongs to a run that died.
  const std::string temp_prefix = "." + name + ".tmp-";
  for (const fs::directory_entry& entry : fs::directory_iterator(parent, ec)) {
    if (entry.path().filename().string().rfind(temp_prefix, 0) == 0) {
      std::error_code ignored;
      fs::remove_all(entry.path(), ignored);
    }
  }

  std::string pattern = (parent / (temp_prefix + "XXXXXX")).string();
  if (::mkdtemp(pattern.data()) == nullptr) {
    error = "cannot create a temporary directory in " + parent.string() + ": " + errno_text(errno);
    return nullptr;
  }
  set->temp_dir_ = pattern;
  // mkdtemp makes the directory private (0700); give it the target's mode, or mkdir's default.
  struct stat target_st {};
  if (::stat(set->target_.c_str(), &target_st) == 0) {
    ::chmod(set->temp_dir_.c_str(), target_st.st_mode & 07777);
  } else {
    const mode_t mask = ::umask(0);
    ::umask(mask);
    ::chmod(set->temp_dir_.c_str(), 0777 & ~mask);
  }
  arm_signal_cleanup(set->temp_dir_, names, set->lock_path_);
  for (const std::string& file_name : names) {
    const std::string path = set->temp_dir_ + "/" + file_name;
    std::FILE* f = std::fopen(path.c_str(), "w");
    if (f == nullptr) {
      error = "cannot write " + path + ": " + errno_text(errno);
      return nullptr;  // the destructor removes what was made
    }
    set->files_.push_back(f);
  }
  return set;
}

OutputSet::~OutputSet() {
  if (!done_) discard();
}

void OutputSet::close_files() noexcept {
  for (std::FILE*& f : files_) {
    if (f != nullptr) std::fclose(f);
    f = nullptr;
  }
}

void OutputSet::release() noexcept {
  disarm_signal_cleanup();
  if (lock_fd_ >= 0) {
    ::unlink(lock_path_.c_str());  // while still held: no one can take a lock on this file
    ::close(lock_fd_);
    lock_fd_ = -1;
  }
  done_ = true;
}

void OutputSet::discard() noexcept {
  if (done_) return;
  close_files();
  if (!temp_dir_.empty()) {
    std::error_code ignored;
    fs::remove_all(temp_dir_, ignored);
  }
  release();
}

bool OutputSet::commit(std::string& error) {
  if (done_) {
    error = "the output set was already committed or discarded";
    return false;
  }
  for (std::size_t k = 0; k < files_.size(); ++k) {
    std::FILE* f = files_[k];
    files_[k] = nullptr;
    const bool written = std::fflush(f) == 0 && std::ferror(f) == 0;
    const int err = errno;
    const bool synced = written && ::fsync(fileno(f)) == 0;
    const bool closed = std::fclose(f) == 0;
    if (!written || !synced || !closed) {
      error = "cannot write " + temp_dir_ + "/" + names_[k] + ": " + errno_text(err);
      discard();
      return false;
    }
  }
  std::error_code ec;
  std::error_code missing;
  if (fs::exists(fs::symlink_status(target_, missing))) {
    // Carry the target's other files over (hard links: the originals stay untouched until the
    // swap), then swap the directories.
    for (const fs::directory_entry& entry : fs::directory_iterator(target_, ec)) {
      const std::string file_name = entry.path().filename().string();
      bool ours = false;
      for (const std::string& n : names_)
        ours = ours || n == file_name;
      if (ours) continue;
      const std::string to = temp_dir_ + "/" + file_name;
      if (::link(entry.path().c_str(), to.c_str()) != 0) {
        error = "cannot keep " + entry.path().string() + " in the new output: " + errno_text(errno);
        discard();
        return false;
      }
    }
    if (ec) {
      error = "cannot list " + target_ + ": " + ec.message();
      discard();
      return false;
    }
    int err = 0;
    if (!rename_exchange(temp_dir_, target_, err)) {
      if (err != EINVAL && err != ENOSYS && err != ENOTSUP) {
        error = "cannot replace " + target_ + ": " + errno_text(err);
        discard();
        return false;
      }
      // No exchange on this file system: move the old set aside (onto an empty placeholder
      // directory, which rename replaces), then the new one in; put the old one back on failure.
      std::string aside = temp_dir_ + ".old-XXXXXX";
      if (::mkdtemp(aside.data()) == nullptr || ::rename(target_.c_str(), aside.c_str()) != 0) {
        error = "cannot replace " + target_ + ": " + errno_text(errno);
        ::rmdir(aside.c_str());
        discard();
        return false;
      }
      if (::rename(temp_dir_.c_str(), target_.c_str()) != 0) {
        error = "cannot replace " + target_ + ": " + errno_text(errno);
        ::rename(aside.c_str(), target_.c_str());
        discard();
        return false;
      }
      std::error_code ignored;
      fs::remove_all(aside, ignored);
      release();
      return true;
    }
    // temp_dir_ now holds the previous set.
    std::error_code ignored;
    fs::remove_all(temp_dir_, ignored);
    release();
    return true;
  }
  if (::rename(temp_dir_.c_str(), target_.c_str()) != 0) {
    error = "cannot create " + target_ + ": " + errno_text(errno);
    discard();
    return false;
  }
  release();
  return true;
}

// ---------------------------------------------------------------------------------------------

std::unique_ptr<OutputFile> OutputFile::open(const std::string& path, std::string& error) {
  std::unique_ptr<OutputFile> out(new OutputFile());
  const fs::path target(path);
  if (path.empty() || !target.has_filename()) {
    error = "'" + path + "' is not a file name";
    return nullptr;
  }
  std::error_code ec;
  if (fs::is_directory(target, ec)) {
    error = "cannot write " + path + ": it is a directory";
    return nullptr;
  }
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::string pattern = (dir / ("." + target.filename().string() + ".tmp-XXXXXX")).string();
  const int fd = ::mkstemp(pattern.data());
  if (fd < 0) {
    error = "cannot write " + path + ": " + errno_text(errno);
    return nullptr;
  }
  // mkstemp makes the file private (0600); give it fopen's default mode.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  out->path_ = path;
  out->temp_path_ = pattern;
  out->file_ = ::fdopen(fd, "w");
  if (out->file_ == nullptr) {
    error = "cannot write " + path + ": " + errno_text(errno);
    ::close(fd);
    return nullptr;  // the destructor removes the temporary
  }
  return out;
}

OutputFile::~OutputFile() {
  if (!done_) discard();
}

void OutputFile::discard() noexcept {
  if (done_) return;
  if (file_ != nullptr) std::fclose(file_);
  file_ = nullptr;
  if (!temp_path_.empty()) ::unlink(temp_path_.c_str());
  done_ = true;
}

bool OutputFile::commit(std::string& error) {
  if (done_ || file_ == nullptr) {
    error = "the output file was already committed or discarded";
    return false;
  }
  const bool written = std::fflush(file_) == 0 && std::ferror(file_) == 0;
  const int err = errno;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!written || !closed) {
    error = "cannot write " + path_ + ": " + errno_text(err);
    discard();
    return false;
  }
  if (::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    error = "cannot write " + path_ + ": " + errno_text(errno);
    discard();
    return false;
  }
  done_ = true;
  return true;
}

}  // namespace fuzzypid::cli
