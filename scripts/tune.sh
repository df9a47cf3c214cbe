#!/usr/bin/env bash
# Regenerates the tuned controller files and the seed study (docs/tuning.md). Every family gets the
# same total budget of objective evaluations on the training set of CONDITIONS (default
# tuning/robust_drive.toml: a real joint's delay, current loop, gear and encoder), whose last four
# conditions are held back for validation (--validation 4):
#   pid, scheduled, fuzzy   one run of BUDGET evaluations
#   fuzzy-rules             staged: pid BUDGET/16 -> scheduled 7 BUDGET/16 -> fuzzy-rules BUDGET/2,
#                           each stage started from the last one's result
#   scheduled_staged        the control of that: pid BUDGET/16 -> scheduled 15 BUDGET/16 (the same
#                           start, the same total, no rule table)
# Outputs:
#   controllers/tuned_{pid,scheduled,fuzzy,fuzzy_rules,scheduled_staged}.toml   seed 1
#   out/seeds/<family>_seed<S>.toml                            seeds 1..SEEDS (default 5)
# then every seed's file on all sets with sim_ab, summarised by scripts/seed_study.py.
#   BUDGET=N   evaluations per controller (default 4000)    SEEDS=N   seeds (default 5)
#   CONDITIONS=FILE  the condition file (default tuning/robust_drive.toml)
#   SEARCH_FILTER=0  keep the start's derivative filter instead of searching it (--keep-filter)
#   THREADS=N  threads per run (default: all cores)          SKIP_SEEDS=1   only seed 1
#   RULES_ARGS="..."  the fuzzy-rules stage's regulariser (default: the documented defaults)
#   RESUME=1   keep the seed files that exist (the runs are deterministic for a seed)
#   BASE=FILE  every run starts from FILE's units and PID options (--base), e.g. a PID whose
#              derivative is the velocity observer, whose bandwidth is then searched too
#   CHATTER_WEIGHT=W CHATTER_LIMIT=L   the objective's chatter weight above L % reversals (defaults
#                      300 and 5: docs/tuning.md, "Chatter")
#   FAMILIES="pid ..."  the families to tune (default: all five)
#   MIN_DISK_MARGIN=A  every candidate keeps a disk margin of at least A (--min-disk-margin; default 0)
#   SEEDS_DIR=DIR      where the seed files and the evaluation go (default out/seeds)
#   PER_JOINT_BANDWIDTH=1  search a bandwidth scale for joints 2-6 too (--per-joint-bandwidth)
# The controllers shipped before the drive re-tune came from
#   CONDITIONS=tuning/robust.toml CHATTER_WEIGHT=0 CHATTER_LIMIT=0 SEARCH_FILTER=0 BUDGET=64000 scripts/tune.sh
set -euo pipefail
cd "$(dirname "$0")/.."
budget="${BUDGET:-4000}"
conditions="${CONDITIONS:-tuning/robust_drive.toml}"
filter=--search-filter
if [ "${SEARCH_FILTER:-1}" = 0 ]; then filter=--keep-filter; fi
seeds="${SEEDS:-5}"
threads="${THREADS:-$(nproc)}"
rules_args="${RULES_ARGS:-}"
families="${FAMILIES:-pid scheduled fuzzy fuzzy_rules scheduled_staged}"
seeds_dir="${SEEDS_DIR:-out/seeds}"
bash scripts/install-deps.sh
# shellcheck disable=SC2086
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release ${FUZZYPID_CMAKE_ARGS:-} >/dev/null
cmake --build build -j "$(nproc)" --target fuzzypid_cli sim_ab
stages="pid:$((budget / 16)),scheduled:$((budget * 7 / 16)),fuzzy-rules:$((budget - budget / 16 - budget * 7 / 16))"
control="pid:$((budget / 16)),scheduled:$((budget - budget / 16))"
# tune_one FAMILY SEED OUT: each run prints its stages, evaluations, wall time and rate.
tune_one() {
  local common=(--conditions "${conditions}" --set training --validation 4 --seed "$2"
                --chatter-weight "${CHATTER_WEIGHT:-300}" --chatter-limit "${CHATTER_LIMIT:-5}"
                --min-disk-margin "${MIN_DISK_MARGIN:-0}"
                "${filter}" --threads "${threads}" --quiet --out "$3")
  if [ "${PER_JOINT_BANDWIDTH:-0}" = 1 ]; then common+=(--per-joint-bandwidth); fi
  if [ -n "${BASE:-}" ]; then common+=(--base "${BASE}"); fi
  if [ "$1" = fuzzy_rules ]; then
    # shellcheck disable=SC2086
    build/bin/fuzzypid tune --stages "${stages}" ${rules_args} "${common[@]}"
  elif [ "$1" = scheduled_staged ]; then
    build/bin/fuzzypid tune --stages "${control}" "${common[@]}"
  else
    build/bin/fuzzypid tune --family "$1" --budget "${budget}" "${common[@]}"
  fi
}
mkdir -p "${seeds_dir}"
last="${seeds}"
if [ "${SKIP_SEEDS:-0}" = 1 ]; then last=1; fi
for seed in $(seq 1 "${last}"); do
  for family in ${families}; do
    out="${seeds_dir}/${family}_seed${seed}.toml"
    if [ "${RESUME:-0}" = 1 ] && [ -f "${out}" ]; then echo "== ${family} seed ${seed}: kept"; continue; fi
    echo "== ${family} seed ${seed}"
    tune_one "${family}" "${seed}" "${out}"
  done
done
for family in ${families}; do
  # The file records its conditions relative to its own folder: one level up from controllers/
  # (the seeds' folder is two levels below the project).
  sed 's|^conditions = "\.\./\.\./|conditions = "../|' "${seeds_dir}/${family}_seed1.toml" \
    >"controllers/tuned_${family}.toml"
done
args=(--controller controllers/paper_pid.toml --controller controllers/paper_fuzzy.toml)
for f in "${seeds_dir}"/*_seed*.toml; do args+=(--controller "$f"); done
build/bin/sim_ab --quiet --allow-faults --conditions "${conditions}" "${args[@]}" --out "${seeds_dir}/eval"
/usr/bin/python3 scripts/seed_study.py "${seeds_dir}/eval"
