// A fuzzer's input as a command line, for the argument-parser targets: the bytes split at NUL
// into argv[1..] after `program` (a trailing non-empty piece is the last argument), with stdout
// sent to /dev/null so that --help and usage messages do not flood the fuzzer's output.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace fuzzypid::fuzz {

class CommandLine {
 public:
  CommandLine(const char* program, const std::uint8_t* data, std::size_t size) : args_{program} {
    std::string current;
    for (std::size_t k = 0; k < size; ++k) {
      if (data[k] == 0) {
        args_.push_back(current);
        current.clear();
      } else {
        current.push_back(static_cast<char>(data[k]));
      }
    }
    if (!current.empty()) args_.push_back(current);
    for (const std::string& a : args_)
      argv_.push_back(a.c_str());
    argv_.push_back(nullptr);
    static std::FILE* const null_out = std::freopen("/dev/null", "w", stdout);
    (void)null_out;
  }

  int argc() const noexcept { return static_cast<int>(args_.size()); }
  const char* const* argv() const noexcept { return argv_.data(); }

 private:
  std::vector<std::string> args_;
  std::vector<const char*> argv_;
};

}  // namespace fuzzypid::fuzz
