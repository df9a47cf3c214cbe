#!/usr/bin/env bash
# The fronts of the four families on the ER50's drive training set at one equal budget
# (docs/tuning.md, "Fronts"): each family's front over itae, effort, chatter and overshoot, tuned
# on the training set of CONDITIONS and run, once found, on its held-out set (--report-set: the
# search never sees it), then the hypervolume of every front on the held-out columns against one
# common reference point, and a plot.
#   BUDGET=N      evaluations per family (default 4000)     SEED=N   (default 1)
#   CONDITIONS=F  (default tuning/robust_drive.toml)        OUT=DIR  (default out/fronts)
#   THREADS=N     threads per run (default: all cores)
# Outputs: OUT/<family>/ (front.csv, point_NNN.toml), OUT/<family>.txt (the tune's report),
# OUT/union_{training,held_out}.md (scripts/front_union.py), OUT/hypervolume_{training,held_out}.csv
# and OUT/fronts_{training,held_out}.png (scripts/plot_front.py).
set -euo pipefail
cd "$(dirname "$0")/.."
budget="${BUDGET:-4000}"
seed="${SEED:-1}"
conditions="${CONDITIONS:-tuning/robust_drive.toml}"
out="${OUT:-out/fronts}"
threads="${THREADS:-$(nproc)}"
bash scripts/install-deps.sh
# shellcheck disable=SC2086
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release ${FUZZYPID_CMAKE_ARGS:-} >/dev/null
cmake --build build -j "$(nproc)" --target fuzzypid_cli
mkdir -p "$out"
families=(pid scheduled fuzzy fuzzy-rules)
for family in "${families[@]}"; do
  build/bin/fuzzypid tune --family "$family" --objectives itae,effort,chatter,overshoot \
    --conditions "$conditions" --report-set held-out --budget "$budget" --seed "$seed" \
    --threads "$threads" --quiet --front-out "$out/$family" | tee "$out/$family.txt" | tail -1
done
dirs=()
for family in "${families[@]}"; do dirs+=("$out/$family"); done
/usr/bin/python3 scripts/front_union.py "${dirs[@]}" --on training | tee "$out/union_training.md"
/usr/bin/python3 scripts/front_union.py "${dirs[@]}" --on validation | tee "$out/union_held_out.md"
# Points with a faulted run (every objective + the fault cost, 1000) are left out of the volumes.
/usr/bin/python3 scripts/plot_front.py "${dirs[@]}" --on training --drop-at 1000 \
  --out "$out/fronts_training.png" | tee "$out/hypervolume_training.csv"
/usr/bin/python3 scripts/plot_front.py "${dirs[@]}" --on validation --drop-at 1000 \
  --out "$out/fronts_held_out.png" | tee "$out/hypervolume_held_out.csv"
