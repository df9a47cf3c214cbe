#!/usr/bin/env bash
# Re-tunes the UR5-class example's controllers (docs/your_robot.md) on the drive plant of
# tuning/ur5_class_drive.toml, as scripts/tune.sh tunes the ER50's: the training set with its last
# four conditions held back for validation (--validation 4), the objective's defaults (chatter
# weight 300 above 5 % reversals, the derivative filter searched), from
# tuning/ur5_class_base.toml (the paper's PID with gravity feed-forward), one seed, BUDGET
# evaluations per family (default 4000). Then every
# controller on every set of the file with sim_ab.
# Outputs: controllers/ur5_class_tuned_{pid,scheduled,fuzzy}.toml, out/ur5_drive/ (the runs).
#   BUDGET=N  SEED=N (default 1)  THREADS=N (default: all cores)
#   CONDITIONS=FILE    the condition file (default tuning/ur5_class_drive.toml)
#   FAMILIES="pid ..." the families to tune (default: pid scheduled fuzzy)
#   MIN_DISK_MARGIN=A  every candidate keeps a disk margin of at least A (default 0: none)
#   CHATTER_WEIGHT=W   the objective's chatter weight above 5 % reversals (default 300)
#   PER_JOINT_BANDWIDTH=1  search a bandwidth scale for joints 2-6 too (--per-joint-bandwidth)
set -euo pipefail
cd "$(dirname "$0")/.."
budget="${BUDGET:-4000}"
seed="${SEED:-1}"
threads="${THREADS:-$(nproc)}"
conditions="${CONDITIONS:-tuning/ur5_class_drive.toml}"
families="${FAMILIES:-pid scheduled fuzzy}"
per_joint=""
if [ "${PER_JOINT_BANDWIDTH:-0}" = 1 ]; then per_joint=--per-joint-bandwidth; fi
bash scripts/install-deps.sh
# shellcheck disable=SC2086
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release ${FUZZYPID_CMAKE_ARGS:-} >/dev/null
cmake --build build -j "$(nproc)" --target fuzzypid_cli sim_ab
mkdir -p out/ur5_drive
for family in ${families}; do
  echo "== ${family}"
  # shellcheck disable=SC2086
  build/bin/fuzzypid tune --family "${family}" --conditions "${conditions}" --set training \
    --base tuning/ur5_class_base.toml --validation 4 --budget "${budget}" --seed "${seed}" \
    --chatter-weight "${CHATTER_WEIGHT:-300}" --min-disk-margin "${MIN_DISK_MARGIN:-0}" \
    --threads "${threads}" --quiet ${per_joint} --out "out/ur5_drive/${family}.toml"
  # The file records its conditions, robot and path relative to its own folder: one level up
  # from controllers/.
  sed 's|"\.\./\.\./|"../|g' "out/ur5_drive/${family}.toml" \
    >"controllers/ur5_class_tuned_${family}.toml"
done
args=(--controller controllers/paper_pid.toml --controller controllers/paper_fuzzy.toml)
for family in pid scheduled fuzzy; do
  args+=(--controller "controllers/ur5_class_tuned_${family}.toml")
done
build/bin/sim_ab --quiet --allow-faults --conditions "${conditions}" "${args[@]}" --out out/ur5_drive/eval
/usr/bin/python3 scripts/summarize_sim.py out/ur5_drive/eval --drive
