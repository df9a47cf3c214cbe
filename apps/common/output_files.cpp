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
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace fuzzypid::cli {
namespace {

namespace fs = std::filesystem;

std::string errno_text(int err) {
  return std::strerror(err);
}

std::string in_quotes(const std::string& path) {
  return "'" + path + "'";
}

// ---------------------------------------------------------------------------------------------
// Clean-up on SIGINT/SIGTERM/SIGHUP of the outputs being written: a fixed table of paths (the open
// sets' files, temporary directories and lock files, the open files' temporaries and lock files),
// filled before the handler can need them. The handler only uses async-signal-safe calls (unlink,
// rmdir, signal, raise) on those prepared paths: files first, then the emptied directories.

enum class Removal : int { None = 0, Unlink = 1, Rmdir = 2 };
constexpr std::size_t kMaxSignalPaths = 64;
char g_signal_paths[kMaxSignalPaths][PATH_MAX];
volatile std::sig_atomic_t g_signal_kind[kMaxSignalPaths];  // a Removal; None for a free slot
std::size_t g_signal_users = 0;                             // slots in use
constexpr std::array<int, 3> kCleanedSignals = {SIGINT, SIGTERM, SIGHUP};
std::array<bool, 3> g_installed{};  // whether our handler replaced the default one
std::array<struct sigaction, 3> g_previous{};

extern "C" void remove_on_signal(int sig) {
  for (const Removal pass : {Removal::Unlink, Removal::Rmdir})
    for (std::size_t k = 0; k < kMaxSignalPaths; ++k)
      if (g_signal_kind[k] == static_cast<int>(pass))
        (void)(pass == Removal::Unlink ? ::unlink(g_signal_paths[k]) : ::rmdir(g_signal_paths[k]));
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

// Installs the handler for each signal whose disposition is the default (death). A tool that
// handles a signal itself (rt_loop stops its loop and commits) keeps its handler, and finishes or
// discards its outputs on its own.
void install_signal_cleanup() noexcept {
  for (std::size_t i = 0; i < kCleanedSignals.size(); ++i) {
    g_installed[i] = false;
    if (sigaction(kCleanedSignals[i], nullptr, &g_previous[i]) != 0) continue;
    if ((g_previous[i].sa_flags & SA_SIGINFO) != 0 || g_previous[i].sa_handler != SIG_DFL) continue;
    struct sigaction sa {};
    sa.sa_handler = remove_on_signal;
    sigemptyset(&sa.sa_mask);
    g_installed[i] = sigaction(kCleanedSignals[i], &sa, nullptr) == 0;
  }
}

// Puts the default back where ours still is (not over a handler the tool set meanwhile).
void restore_signal_cleanup() noexcept {
  for (std::size_t i = 0; i < kCleanedSignals.size(); ++i) {
    if (!g_installed[i]) continue;
    struct sigaction current {};
    if (sigaction(kCleanedSignals[i], nullptr, &current) == 0 &&
        (current.sa_flags & SA_SIGINFO) == 0 && current.sa_handler == remove_on_signal)
      sigaction(kCleanedSignals[i], &g_previous[i], nullptr);
    g_installed[i] = false;
  }
}

// Adds `path` to the table; the handlers are installed with the first path. Returns the slot, or
// -1 when the table is full or the path too long (left to the next run's clean-up).
int remove_on_signal_add(const std::string& path, Removal kind) {
  if (path.size() >= PATH_MAX) return -1;
  for (std::size_t k = 0; k < kMaxSignalPaths; ++k) {
    if (g_signal_kind[k] != static_cast<int>(Removal::None)) continue;
    std::memcpy(g_signal_paths[k], path.c_str(), path.size() + 1);
    if (g_signal_users++ == 0) install_signal_cleanup();
    g_signal_kind[k] = static_cast<int>(kind);  // last: the slot is complete before it is seen
    return static_cast<int>(k);
  }
  return -1;
}

// Frees the slots; the previous handlers are restored with the last one.
void remove_on_signal_drop(std::vector<int>& slots) noexcept {
  for (const int k : slots) {
    if (k < 0 || g_signal_kind[k] == static_cast<int>(Removal::None)) continue;
    g_signal_kind[k] = static_cast<int>(Removal::None);
    if (--g_signal_users == 0) restore_signal_cleanup();
  }
  slots.clear();
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
  set->signal_slots_.push_back(remove_on_signal_add(set->lock_path_, Removal::Unlink));
  set->signal_slots_.push_back(remove_on_signal_add(set->temp_dir_, Removal::Rmdir));
  for (const std::string& file_name : names)
    set->signal_slots_.push_back(
        remove_on_signal_add(set->temp_dir_ + "/" + file_name, Removal::Unlink));
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
  remove_on_signal_drop(signal_slots_);
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
// Output paths (output_files.hpp, "The contract of an output path").

namespace {

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

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

// Resolves `path` to the file an output replaces: itself, or what its symbolic link names. Sets
// `exists` and, when it exists, `st` (of the final file). "" or the reason.
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

}  // namespace

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

// ---------------------------------------------------------------------------------------------

namespace {

// Removes `.<name>.<tool>.<pid>.tmp` in `dir` whose process no longer exists.
void remove_stale_temporaries(const std::string& dir, const std::string& name,
                              const std::string& tool) {
  const std::string prefix = "." + name + "." + tool + ".";
  const std::string suffix = ".tmp";
  DIR* d = ::opendir(dir.c_str());
  if (d == nullptr) return;
  while (const dirent* e = ::readdir(d)) {
    const std::string entry = e->d_name;
    if (entry.size() <= prefix.size() + suffix.size() || entry.rfind(prefix, 0) != 0 ||
        entry.compare(entry.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    const std::string digits =
        entry.substr(prefix.size(), entry.size() - prefix.size() - suffix.size());
    if (digits.empty() || digits.size() > 9 ||
        digits.find_first_not_of("0123456789") != std::string::npos)
      continue;
    const long pid = std::strtol(digits.c_str(), nullptr, 10);
    if (pid <= 0) continue;
    if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH)
      ::unlinkat(::dirfd(d), entry.c_str(), 0);
  }
  ::closedir(d);
}

void sync_folder(const std::string& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);  // best effort: the file itself is already on disk
  ::close(fd);
}

std::string folder_of(const std::string& path) {
  const fs::path p(path);
  return p.has_parent_path() ? p.parent_path().string() : ".";
}

}  // namespace

std::unique_ptr<OutputFile> OutputFile::open(const std::string& path, std::string& error,
                                             const std::string& tool) {
  std::unique_ptr<OutputFile> out(new OutputFile());
  bool exists = false;
  struct stat st {};
  if (std::string bad = resolve_output(path, out->target_, exists, st); !bad.empty()) {
    error = bad;
    return nullptr;
  }
  const std::string dir = folder_of(out->target_);
  const std::string name = fs::path(out->target_).filename().string();
  out->path_ = path;
  out->lock_path_ = (fs::path(dir) / ("." + name + ".lock")).string();
  out->lock_fd_ = lock_file(out->lock_path_, "the output file " + in_quotes(path), error);
  if (out->lock_fd_ < 0) {
    out->done_ = true;  // nothing of ours to remove
    return nullptr;
  }
  out->signal_slots_.push_back(remove_on_signal_add(out->lock_path_, Removal::Unlink));
  remove_stale_temporaries(dir, name, tool);
  const std::string temp =
      (fs::path(dir) / ("." + name + "." + tool + "." + std::to_string(::getpid()) + ".tmp"))
          .string();
  ::unlink(temp.c_str());  // ours by name: a leftover of an earlier open in this process
  // The new file gets the mode of the file it replaces, else the usual 0666 & ~umask.
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC,
                        exists ? (st.st_mode & 07777) : 0666);
  if (fd < 0) {
    error = "cannot write " + path + ": " + errno_text(errno);
    return nullptr;
  }
  out->temp_path_ = temp;
  out->signal_slots_.push_back(remove_on_signal_add(temp, Removal::Unlink));
  if (exists) ::fchmod(fd, st.st_mode & 07777);  // not masked by the umask
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

void OutputFile::release() noexcept {
  remove_on_signal_drop(signal_slots_);
  if (lock_fd_ >= 0) {
    ::unlink(lock_path_.c_str());  // while still held: no one can take a lock on this file
    ::close(lock_fd_);
    lock_fd_ = -1;
  }
  done_ = true;
}

void OutputFile::discard() noexcept {
  if (done_) return;
  if (file_ != nullptr) std::fclose(file_);
  file_ = nullptr;
  if (!temp_path_.empty()) ::unlink(temp_path_.c_str());
  release();
}

bool OutputFile::commit(std::string& error) {
  if (done_ || file_ == nullptr) {
    error = "the output file was already committed or discarded";
    return false;
  }
  errno = 0;
  bool ok = std::fflush(file_) == 0 && std::ferror(file_) == 0;
  int err = errno;
  if (ok && ::fsync(fileno(file_)) != 0) {
    ok = false;
    err = errno;
  }
  if (std::fclose(file_) != 0 && ok) {
    ok = false;
    err = errno;
  }
  file_ = nullptr;
  if (!ok) {
    error = "cannot write " + path_ + ": " + errno_text(err != 0 ? err : EIO) +
            " (the previous file, if any, is unchanged)";
    discard();
    return false;
  }
  // The target may have changed since open: still never replace anything but a regular file.
  struct stat st {};
  if (::lstat(target_.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    error = "cannot write " + path_ + ": it is now " + kind_of(st.st_mode) + "; left unchanged";
    discard();
    return false;
  }
  if (::rename(temp_path_.c_str(), target_.c_str()) != 0) {
    error = "cannot write " + path_ + ": " + errno_text(errno);
    discard();
    return false;
  }
  sync_folder(folder_of(target_));
  release();
  return true;
}

std::string write_output_file(const std::string& path, std::string_view text,
                              const std::string& tool) {
  std::string error;
  const std::unique_ptr<OutputFile> out = OutputFile::open(path, error, tool);
  if (!out) return error;
  if (!text.empty() && std::fwrite(text.data(), 1, text.size(), out->file()) != text.size()) {
    const int err = errno;
    out->discard();
    return "cannot write " + path + ": " + errno_text(err != 0 ? err : EIO) +
           " (the previous file, if any, is unchanged)";
  }
  if (!out->commit(error)) return error;
  return {};
}

}  // namespace fuzzypid::cli
