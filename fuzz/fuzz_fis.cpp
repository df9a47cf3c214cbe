// libFuzzer target for the MATLAB .fis reader.
#include "fuzz_rule_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzzypid::fuzz::run(data, size, &fuzzypid::rulefile::parse_fis);
}
