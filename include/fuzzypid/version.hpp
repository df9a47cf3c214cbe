// Library version.
#pragma once

#define FUZZYPID_VERSION_MAJOR 0
#define FUZZYPID_VERSION_MINOR 1
#define FUZZYPID_VERSION_PATCH 0

namespace fuzzypid {
inline constexpr const char* kVersion = "0.1.0";
}  // namespace fuzzypid
