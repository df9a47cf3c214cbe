// libFuzzer target for the IEC 61131-7 .fcl reader.
#include "fuzz_rule_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzzypid::fuzz::run(data, size, &fuzzypid::rulefile::parse_fcl);
}
