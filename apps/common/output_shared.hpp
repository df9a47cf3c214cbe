// What the output parts share (output_paths.cpp, output_set.cpp, output_file.cpp; not part of the
// tools' API): clean-up of the outputs being written when SIGINT/SIGTERM/SIGHUP arrives, an
// exclusive lock file, the resolution of an output path, and the small helpers of their messages.
#pragma once

#include <sys/stat.h>

#include <filesystem>
#include <string>
#include <vector>

namespace fuzzypid::cli::detail {

std::string errno_text(int err);
std::string in_quotes(const std::string& path);

// What the signal handler does with a registered path.
enum class Removal : int { None = 0, Unlink = 1, Rmdir = 2 };
// Adds `path` to the handler's fixed table (the handlers are installed with the first path).
// Returns the slot, or -1 when the table is full or the path too long (left to the next run's
// clean-up).
int remove_on_signal_add(const std::string& path, Removal kind);
// Frees the slots; the previous handlers are restored with the last one.
void remove_on_signal_drop(std::vector<int>& slots) noexcept;

// Takes an exclusive flock on `path` (created if needed) without waiting. Returns the descriptor
// or -1 with `error` set (`what` names the output in it).
int lock_file(const std::string& path, const std::string& what, std::string& error);
// True when `dir` is the current directory or one of its ancestors.
bool contains_cwd(const std::filesystem::path& dir);
// Swaps the two paths atomically (renameat2 RENAME_EXCHANGE); false with `err` set.
bool rename_exchange(const std::string& a, const std::string& b, int& err);

// What a file of this mode is, for messages ("a folder", "a FIFO", ...).
const char* kind_of(mode_t mode);
// Resolves `path` to the file an output replaces: itself, or what its symbolic link names. Sets
// `exists` and, when it exists, `st` (of the final file). "" or the reason (output_paths.cpp).
std::string resolve_output(const std::string& path, std::string& target, bool& exists,
                           struct stat& st);

}  // namespace fuzzypid::cli::detail
