// Output files that are either complete or absent.
//
// OutputSet writes a set of files for a directory and commits them as a whole: the files are
// written into a fresh, uniquely named temporary directory beside the target, and the commit
// swaps that directory with the target in one rename (renameat2 RENAME_EXCHANGE; where the file
// system lacks it, two renames that never expose a mixed set). A reader of the target therefore
// sees either the previous complete set or the new one. While a set is open:
//   - the target is locked (flock on `.<name>.lock` beside it): a second writer of the same
//     directory is refused instead of interleaving with the first;
//   - SIGINT, SIGTERM and SIGHUP remove the temporary directory and the lock file before the
//     process dies with the signal, so an interrupted run leaves nothing behind; temporaries of a
//     run killed outright (SIGKILL, power loss) are removed by the next run into the same
//     directory.
// Regular files in the target that are not part of the set (plots made from an earlier run, say)
// are carried over into the new directory. A target holding subdirectories or other special
// files, the current directory or one of its ancestors is refused: it cannot be replaced whole
// without taking the user's other data with it.
//
// OutputFile is the same for one file, and every tool writes its output files through it
// (write_output_file for a text made at once): the text goes to `.<name>.<tool>.<pid>.tmp` in the
// target's folder, is flushed and fsync'ed, and is renamed over the target only when complete; on
// any failure the temporary is removed, the previous file is left as it was and the error names
// the reason (strerror). From open to commit or discard the target is locked like a set's
// (`.<name>.lock` beside it, the same lock file as a set of that name), so a second writer of the
// same file -- another run of any tool -- is refused at open instead of both reporting success
// while one result is lost; SIGINT, SIGTERM and SIGHUP remove the temporary and the lock file.
// Temporaries of the same tool whose process is gone (a run killed outright) are removed when the
// next run opens the same target.
//
// The contract of an output path (docs/robustness.md, "Outputs"), checked by check_output_path()
// when the arguments are parsed, before any work, and again when the file is opened:
//   - the name is not empty and names a file (not `dir/`, `.` or `..`);
//   - its folder exists, is a folder, and is writable (a folder or file whose mode grants no write
//     permission to anyone is refused even for root, who could otherwise write it);
//   - the target is absent or a regular file: a folder, a device, a FIFO or a socket is refused
//     (never replaced, never written through); a symbolic link is followed, and the file it names
//     is replaced, so the link stays a link;
//   - the target is not the same file (device and inode) as any input of the run, whatever its
//     spelling (symbolic links, `./`, hard links), nor the file standard output or error goes
//     to; a target that does not exist is no input.
// A refused path is a usage error: the tools exit 2 with the message before doing anything.
#pragma once

#include <cstddef>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace fuzzypid::cli {

// "" when `path` may be written as an output file of a run reading `inputs` (paths; empty ones are
// ignored), else the reason, starting with the path.
[[nodiscard]] std::string check_output_path(const std::string& path,
                                            const std::vector<std::string>& inputs);

// The same for an output folder replaced as a whole (OutputSet): `dir` is not empty, is absent or a
// folder (followed if a symbolic link), its nearest existing ancestor is a writable folder, and no
// input is one of the files `names` inside it.
[[nodiscard]] std::string check_output_dir(const std::string& dir,
                                           const std::vector<std::string>& names,
                                           const std::vector<std::string>& inputs);

// `file` (relative to the current folder, or absolute) as named from the folder of the file `out`
// (how a written file names the files it refers to): relative when both are on one tree, else
// absolute. Symbolic links in the folders are resolved, so the name leads where a reader of `out`
// follows it.
[[nodiscard]] std::string path_from_folder_of(const std::string& out, const std::string& file);

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
  // Opens one more file of the set, `name` (a plain file name, not one of the set's yet), for a
  // set whose names are known only once its contents are: its index is the next one. Null and
  // `error` on failure; the set stays usable.
  [[nodiscard]] std::FILE* add(const std::string& name, std::string& error);
  // Files of the target whose names start with `prefix` are the set's own: at the commit those
  // not written again are left out instead of carried over (a front of fewer points than the
  // last one's leaves no stale point files).
  void replace_all_starting_with(const std::string& prefix) { owned_prefix_ = prefix; }
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
  std::vector<int> signal_slots_;  // the paths a signal removes
  std::string owned_prefix_;       // replace_all_starting_with
  bool done_ = false;
};

class OutputFile {
 public:
  // Checks `path` (check_output_path without inputs), locks it (refused, naming the file, while
  // another run writes it), removes the stale temporaries of `tool` for it, and creates the
  // temporary file `.<name>.<tool>.<pid>.tmp` in the target's folder. Null and `error` on failure.
  static std::unique_ptr<OutputFile> open(const std::string& path, std::string& error,
                                          const std::string& tool = "fuzzypid");

  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  ~OutputFile();  // discards unless committed

  [[nodiscard]] std::FILE* file() const { return file_; }
  // The temporary file's path (until commit).
  [[nodiscard]] const std::string& temporary_path() const { return temp_path_; }
  // Flushes, fsyncs and closes the file, checking every write, checks that the target is still
  // absent or a regular file, and renames the temporary over it (then fsyncs the folder).
  [[nodiscard]] bool commit(std::string& error);
  void discard() noexcept;

 private:
  OutputFile() = default;
  void release() noexcept;  // removes the lock file and releases the lock
  std::string path_;        // as given, for messages
  std::string target_;      // the file replaced: `path_` with a symbolic link resolved
  std::string temp_path_;
  std::string lock_path_;  // .<name>.lock beside the target
  int lock_fd_ = -1;
  std::FILE* file_ = nullptr;
  std::vector<int> signal_slots_;  // the paths a signal removes
  bool done_ = false;
};

// Writes `text` to `path` through an OutputFile. "" on success, else the reason.
[[nodiscard]] std::string write_output_file(const std::string& path, std::string_view text,
                                            const std::string& tool);

}  // namespace fuzzypid::cli
