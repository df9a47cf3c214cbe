#!/usr/bin/env bash
# Regenerates the tuned controller files and the seed study (docs/tuning.md):
#   controllers/tuned_{pid,scheduled,fuzzy}.toml   seed 1, the default budget (16,000 evaluations)
#   out/seeds/<family>_seed<S>.toml                seeds 1..SEEDS (default 5) at the same budget
# on the training set of tuning/robust.toml, then evaluates every seed's file on all sets with
# sim_ab and prints the per-seed held-out ratios (scripts/seed_study.py).
#   BUDGET=N   evaluations per run (default 16000)   SEEDS=N   seeds per family (default 5)
#   THREADS=N  threads per run (default: all cores)  SKIP_SEEDS=1   only the shipped files
set -euo pipefail
cd "$(dirname "$0")/.."
budget="${BUDGET:-16000}"
seeds="${SEEDS:-5}"
threads="${THREADS:-$(nproc)}"
bash scripts/install-deps.sh
# shellcheck disable=SC2086
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release ${FUZZYPID_CMAKE_ARGS:-} >/dev/null
cmake --build build -j "$(nproc)" --target fuzzypid_cli sim_ab
# Each run prints its evaluations, wall time and evaluations per second.
for family in pid scheduled fuzzy; do
  build/bin/fuzzypid tune --family "${family}" --conditions tuning/robust.toml --set training \
    --budget "${budget}" --seed 1 --threads "${threads}" --out "controllers/tuned_${family}.toml"
done
if [ "${SKIP_SEEDS:-0}" = 1 ]; then exit 0; fi
mkdir -p out/seeds
for family in pid scheduled fuzzy; do
  for seed in $(seq 1 "${seeds}"); do
    build/bin/fuzzypid tune --family "${family}" --conditions tuning/robust.toml --set training \
      --budget "${budget}" --seed "${seed}" --threads "${threads}" --quiet \
      --out "out/seeds/${family}_seed${seed}.toml"
  done
done
args=()
for f in out/seeds/*_seed*.toml; do args+=(--controller "$f"); done
build/bin/sim_ab --quiet --conditions tuning/robust.toml "${args[@]}" --out out/seeds/eval
/usr/bin/python3 scripts/seed_study.py out/seeds/eval
