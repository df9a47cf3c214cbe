// The output parts' shared helpers (output_shared.hpp).
#include "output_shared.hpp"

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

namespace fuzzypid::cli::detail {

namespace fs = std::filesystem;

std::string errno_text(int err) {
  return std::strerror(err);
}

std::string in_quotes(const std::string& path) {
  return "'" + path + "'";
}

namespace {

// ---------------------------------------------------------------------------------------------
// Clean-up on SIGINT/SIGTERM/SIGHUP of the outputs being written: a fixed table of paths (the open
// sets' files, temporary directories and lock files, the open files' temporaries and lock files),
// filled before the handler can need them. The handler only uses async-signal-safe calls (unlink,
// rmdir, signal, raise) on those prepared paths: files first, then the emptied directories.

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

}  // namespace

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

}  // namespace fuzzypid::cli::detail
