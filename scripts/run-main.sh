#!/usr/bin/env bash
# The main job: builds the project into build/ and runs the one-joint step-response example,
# writing out/step_response.csv.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release ${FUZZYPID_CMAKE_ARGS:-}
cmake --build build -j "$(nproc)" --target step_response
mkdir -p out
build/bin/step_response > out/step_response.csv
echo "wrote out/step_response.csv"
