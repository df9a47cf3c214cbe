#!/usr/bin/env bash
# Builds the libFuzzer targets of the .fis and .fll readers with clang (ASan + UBSan) in
# build-fuzz/ and runs each for a bounded time from the seed corpus in fuzz/corpus/.
#   FUZZ_SECONDS  time per target (default 30)
# Exits non-zero on any crash, leak or sanitizer report; the failing input is written to
# build-fuzz/crash-* (replay: build-fuzz/bin/fuzz_fis FILE).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${FUZZ_SECONDS:-30}"
CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DFUZZYPID_BUILD_FUZZERS=ON -DFUZZYPID_BUILD_TESTS=OFF -DFUZZYPID_BUILD_APPS=OFF \
  -DFUZZYPID_BUILD_BENCH=OFF -DFUZZYPID_WITH_ROBOT=OFF >/dev/null
cmake --build build-fuzz --target fuzz_fis fuzz_fll
for format in fis fll; do
  work="build-fuzz/corpus-${format}"
  mkdir -p "${work}"
  echo "fuzz_${format}: ${seconds} s"
  # New inputs go to the work corpus; the checked-in seeds are only read.
  build-fuzz/bin/fuzz_${format} -max_total_time="${seconds}" -max_len=8192 -timeout=10 \
    -print_final_stats=1 -artifact_prefix=build-fuzz/ "${work}" "fuzz/corpus/${format}" 2>&1 | tail -n 12
done
