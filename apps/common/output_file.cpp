// OutputFile and write_output_file (output_files.hpp): one output replaced atomically.
#include "output_files.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "output_shared.hpp"

namespace fuzzypid::cli {

namespace fs = std::filesystem;
using detail::errno_text;
using detail::in_quotes;
using detail::kind_of;
using detail::lock_file;
using detail::Removal;
using detail::remove_on_signal_add;
using detail::remove_on_signal_drop;
using detail::resolve_output;

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
