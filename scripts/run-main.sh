#!/usr/bin/env bash
# The main job: builds sim_ab into build/, runs the paper's A/B experiment on every scenario
# (fixed PID, fuzzy PID and an ITAE-tuned fixed PID on the ER50-C20 model), prints the metrics
# table and writes out/trajectory.csv, out/metrics.csv, out/endeffector.csv, out/settings.txt and
# the figures out/*.png. Extra sim_ab options may be passed as arguments (e.g. --scenario paper).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
# shellcheck disable=SC2086
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release ${FUZZYPID_CMAKE_ARGS:-}
cmake --build build -j "$(nproc)" --target sim_ab
if [ $# -eq 0 ]; then set -- --scenario all; fi
build/bin/sim_ab --out out "$@"
/usr/bin/python3 scripts/plot_sim.py --in out --out out
