#!/usr/bin/env bash
# Builds every target (library, apps, benchmarks, tests) into build/ and runs the whole test suite.
# Extra CMake arguments can be passed in FUZZYPID_CMAKE_ARGS.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
# The fuzzylite 8 oracle (pyfuzzylite from PyPI, in a virtual environment of its own) that
# ctest oracle.fuzzylite8_corpus compares every .fll of the corpus with.
[ -x build/oracle-venv/bin/python ] || sh scripts/oracle-venv.sh build/oracle-venv
# shellcheck disable=SC2086
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release ${FUZZYPID_CMAKE_ARGS:-}
cmake --build build -j "$(nproc)"
ctest --test-dir build --output-on-failure -j "$(nproc)" --timeout 600
