// OutputSet (output_files.hpp): a folder of outputs replaced as one.
#include "output_files.hpp"

#include <fcntl.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "output_shared.hpp"

namespace fuzzypid::cli {

namespace fs = std::filesystem;
using detail::contains_cwd;
using detail::errno_text;
using detail::lock_file;
using detail::Removal;
using detail::remove_on_signal_add;
using detail::remove_on_signal_drop;
using detail::rename_exchange;

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

std::FILE* OutputSet::add(const std::string& name, std::string& error) {
  if (done_) {
    error = "the output set was already committed or discarded";
    return nullptr;
  }
  if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos ||
      std::find(names_.begin(), names_.end(), name) != names_.end()) {
    error = "cannot add '" + name + "' to the output set: not a new plain file name";
    return nullptr;
  }
  const std::string path = temp_dir_ + "/" + name;
  const int slot = remove_on_signal_add(path, Removal::Unlink);
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) {
    error = "cannot write " + path + ": " + errno_text(errno);
    std::vector<int> slots{slot};
    remove_on_signal_drop(slots);
    return nullptr;
  }
  signal_slots_.push_back(slot);
  names_.push_back(name);
  files_.push_back(f);
  return f;
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
      bool ours = !owned_prefix_.empty() && file_name.rfind(owned_prefix_, 0) == 0;
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

}  // namespace fuzzypid::cli
