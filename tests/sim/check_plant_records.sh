#!/bin/sh
# What ran is on record: conditions.csv and settings.txt name, per condition, the robot (URDF),
# the path, the tick, the payload in kg, the dynamics, gravity and the armature, and the banner
# prints the plant; so two runs that differ only by --dynamics coupled --gravity --payload-kg 2
# write different files (they once wrote identical ones).
# Usage: check_plant_records.sh <sim_ab> <source dir>
set -u
sim_ab=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
"$sim_ab" --quiet --out "$work/paper" || fail "the paper's plant"
# The paper's PID cannot hold the ER50's shoulder against gravity with a 2 kg tool: faults
# (joint 2 |error| > 1 rad), accepted here.
"$sim_ab" --dynamics coupled --gravity --payload-kg 2 --allow-faults --out "$work/coupled" \
  >/dev/null 2>"$work/err" || fail "coupled: $(cat "$work/err")"
cmp -s "$work/paper/conditions.csv" "$work/coupled/conditions.csv" &&
  fail "conditions.csv identical for two plants"
head -1 "$work/paper/conditions.csv" |
  grep -q ",initial_error,urdf,path,tick_s,payload_kg,dynamics,gravity,armature_kgm2,plant_step_ms,delay_ms,torque_bandwidth_hz,encoder_counts,coulomb_nm,stribeck_nm,stribeck_velocity,coulomb_smoothing,joint_resonance_hz,joint_damping_ratio,backlash_rad$" ||
  fail "conditions.csv header: $(head -1 "$work/paper/conditions.csv")"
grep -q "^paper,scenario,.*/er50_c20.urdf,line,0.050000000000000003,0,decoupled,0,8.5;16;" \
  "$work/paper/conditions.csv" || fail "paper row: $(tail -1 "$work/paper/conditions.csv")"
grep -q "^paper,scenario,.*/er50_c20.urdf,line,0.050000000000000003,2,coupled,1,8.5;16;" \
  "$work/coupled/conditions.csv" || fail "coupled row: $(tail -1 "$work/coupled/conditions.csv")"
grep -q "^condition.paper=set=scenario urdf=.*/er50_c20.urdf path=line tick_s=0.050000000000000003 payload_kg=2 dynamics=coupled gravity=1 armature_kgm2=8.5,16," \
  "$work/coupled/settings.txt" || fail "settings.txt: $(grep '^condition' "$work/coupled/settings.txt")"
grep -q "^sim_ab: plant dynamics coupled, gravity on, payload 2 kg (1 condition)$" "$work/err" ||
  fail "banner: $(cat "$work/err")"
# What real joints have is on record too, in the keys' units.
"$sim_ab" --quiet --delay-ms 10 --encoder-counts 4096 --coulomb-nm 1,2,3,4,5,6 \
  --coulomb-smoothing 0.03 --out "$work/effects" 2>"$work/err" || fail "effects: $(cat "$work/err")"
grep -q ",0,10,0,4096,1;2;3;4;5;6,0;0;0;0;0;0,0,0.029999999999999999,0;0;0;0;0;0,0,0$" \
  "$work/effects/conditions.csv" ||
  fail "effects row: $(tail -1 "$work/effects/conditions.csv")"
"$sim_ab" --delay-ms 10 --encoder-counts 4096 --coulomb-nm 1,2,3,4,5,6 --out "$work/banner" \
  >/dev/null 2>"$work/err" || fail "effects banner run: $(cat "$work/err")"
grep -q "^sim_ab: plant dynamics decoupled, gravity off, payload 0 kg, delay 10 ms, encoder 4096 counts, Coulomb up to 6 N·m (1 condition)$" \
  "$work/err" || fail "effects banner: $(cat "$work/err")"
grep -q " delay_ms=10 torque_bandwidth_hz=0 encoder_counts=4096 coulomb_nm=1,2,3,4,5,6 .* coulomb_smoothing=0.029999999999999999 " \
  "$work/effects/settings.txt" || fail "effects settings: $(grep '^condition' "$work/effects/settings.txt")"
# A controller's derivative source is on record, with the velocity observer's settings.
"$sim_ab" --quiet --controller "$2/tests/sim/data/observer_pid.toml" --out "$work/observer" ||
  fail "observer run"
grep -q " derivative=observer observer_bandwidth_hz=1.2 observer_delay_ticks=1$" \
  "$work/observer/settings.txt" ||
  fail "observer settings: $(grep 'derivative' "$work/observer/settings.txt")"
# The banner is a record too: a run whose standard error cannot be written exits 1.
"$sim_ab" --out "$work/lost" >/dev/null 2>/dev/full && fail "sim_ab exits 0 with its banner lost"
echo "plant records: conditions.csv, settings.txt and the banner name the plant"

