// Output files that are either complete or absent.
//
// OutputSet writes a set of files for a directory and commits them as a whole: the files are
// written into a fresh, uniquely named temporary directory beside the target, and the commit
// swaps that directory with the target in one rename (renameat2 RENAME_EXCHANGE; where the file
// system lacks it, two renames that never expose a mixed set). A reader of the target therefore
// sees either the previous complete set or the new one. While a set is open:
//   - the target is locked (flock on `.<name>.lock` beside it): a second writer of the same
//     directory is refused instead of interleaving with the first;
//   - SIGINT and SIGTERM remove the temporary directory and the lock file before the process
//     dies with the signal, so an interrupted run leaves nothing behind; temporaries of a run
//     killed outright (SIGKILL, power loss) are removed by the next run into the same directory.
// Regular files in the target that are not part of the set (plots made from an earlier run, say)
// are carried over into the new directory. A target holding subdirectories or other special
// files, the current directory or one of its ancestors is refused: it cannot be replaced whole
// without taking the user's other data with it.
//
// OutputFile is the same for one file: written under a unique temporary name in the target's
// directory, renamed over the target on commit, removed otherwise. Opening it before a run checks
// that the target's directory is writable before any work is done.
#pragma once

#include <cstddef>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace fuzzypid::cli {

class OutputSet {
 public:
  // Locks `dir`, removes temporaries left by killed runs, creates the temporary directory and
  // opens `names` in it for writing. Returns null (and a message in `error`) on any failure.
  static std::unique_ptr<OutputSet> open(const std::string& dir,
                                         const std::vector<std::string>& names, std::string& error);

  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;
  // Discards the set unless it was committed.
  ~OutputSet();

  // The open file of names[index].
  [[nodiscard]] std::FILE* file(std::size_t index) const { return files_.at(index); }
  // The directory being written (the temporary one until commit).
  [[nodiscard]] const std::string& temporary_dir() const { return temp_dir_; }

  // Closes every file, checking that every write succeeded, and replaces the target directory.
  // On failure the target is unchanged, the temporary directory removed, and `error` says why.
  [[nodiscard]] bool commit(std::string& error);
  // Removes the temporary directory and releases the lock; the target is unchanged.
  void discard() noexcept;

 private:
  OutputSet() = default;
  void close_files() noexcept;
  void release() noexcept;

  std::string target_;     // the output directory, absolute
  std::string temp_dir_;   // .<name>.tmp-XXXXXX beside it
  std::string lock_path_;  // .<name>.lock beside it
  int lock_fd_ = -1;
  std::vector<std::string> names_;
  std::vector<std::FILE*> files_;
  bool done_ = false;
};

class OutputFile {
 public:
  // Creates a unique temporary file beside `path` (.<name>.tmp-XXXXXX). Null and `error` on
  // failure (e.g. the directory does not exist or is not writable).
  static std::unique_ptr<OutputFile> open(const std::string& path, std::string& error);

  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  ~OutputFile();  // discards unless committed

  [[nodiscard]] std::FILE* file() const { return file_; }
  // Closes the file, checking every write, and renames it to the target path.
  [[nodiscard]] bool commit(std::string& error);
  void discard() noexcept;

 private:
  OutputFile() = default;
  std::string path_;
  std::string temp_path_;
  std::FILE* file_ = nullptr;
  bool done_ = false;
};

}  // namespace fuzzypid::cli
