#!/usr/bin/env bash
# Single-core throughput of LIGGGHTS 3.8 and of grainstorm's CPU backend on
# the same settled bed (bench/settle_bench.cpp; settle_bed.in is its LIGGGHTS
# translation), run back to back and alternated so both see the same machine.
#
#   bench/liggghts/run.sh N [STEPS] [REPEATS] [NP]
#
#   N        spheres (settle_bench --n), e.g. 100000
#   STEPS    timed steps after 20 warm-up steps, the same in both codes (default 1000)
#   REPEATS  runs of each code, alternated LIGGGHTS, grainstorm, ... (default 3)
#   NP       MPI processes for LIGGGHTS (default 1; grainstorm always runs 1 thread)
#
# Environment:
#   GS_SETTLE_BENCH  grainstorm's settle_bench binary (default build/bench/settle_bench)
#   GS_PRECISION     fp32 (settle_bench's default) or fp64 (LIGGGHTS computes in fp64)
#   GS_STEP          time step in grainstorm's contact times (settle_bench --step, default 0.1);
#                    LIGGGHTS steps the same seconds (settle_bench's time_step_s)
#   LIGGGHTS         LIGGGHTS binary (default: liggghts, from `apt-get install liggghts`)
#
# Prints one line per run (with the load average before it) and the best and
# median particle-steps/s of each code. Not part of any test.
set -euo pipefail

N=${1:?usage: run.sh N [STEPS] [REPEATS] [NP]}
STEPS=${2:-1000}
REPEATS=${3:-3}
NP=${4:-1}
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
gs=${GS_SETTLE_BENCH:-$repo/build/bench/settle_bench}
precision=${GS_PRECISION:-fp32}
step=${GS_STEP:-0.1}
lig=${LIGGGHTS:-liggghts}

command -v "$lig" >/dev/null || { echo "run.sh: $lig not found (apt-get install -y liggghts)" >&2; exit 1; }
[ -x "$gs" ] || { echo "run.sh: $gs not found or not executable (build settle_bench, or set GS_SETTLE_BENCH)" >&2; exit 1; }

# The step in seconds, from a run of no timed step (settle_bench refuses one
# beyond its stability limit).
dt=$("$gs" --backend cpu --n 1000 --steps 0 --contacts no --step "$step" | sed -nE 's/.*time_step_s=([^ ]+).*/\1/p')
[ -n "$dt" ] || { echo "run.sh: settle_bench gave no time step for --step $step" >&2; exit 1; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMP_NUM_THREADS=1

# One LIGGGHTS run; prints "rate atoms_at_end ke_at_end contacts_per_sphere".
run_liggghts() {
  local log=$work/liggghts.log
  local cmd=("$lig")
  [ "$NP" -gt 1 ] && cmd=(mpirun --allow-run-as-root -np "$NP" "$lig")
  (cd "$work" && "${cmd[@]}" -in "$here/settle_bed.in" -var N "$N" -var STEPS "$STEPS" -var DT "$dt" -log none) > "$log" 2>&1 ||
    { cat "$log" >&2; return 1; }
  # The second "Loop time" line is the timed run (the first is the warm-up).
  local loop
  loop=$(grep '^Loop time of' "$log" | sed -n 2p | awk '{print $4}')
  # Last thermo line of the timed run and the contact count of the run 0 after it.
  local thermo contacts
  thermo=$(awk -v s=$((STEPS + 20)) '$1 == s && NF == 4 {line=$0} END {print line}' "$log")
  contacts=$(awk -v s=$((STEPS + 20)) '$1 == s && NF == 5 {print $5}' "$log")
  awk -v n="$N" -v s="$STEPS" -v t="$loop" -v th="$thermo" -v c="$contacts" \
    'BEGIN {split(th, a); printf "%.4g atoms=%s ke=%s contacts_per_sphere=%s loop_s=%s\n", n*s/t, a[2], a[3], c, t}'
}

# One grainstorm run; prints "rate wall_s".
run_grainstorm() {
  local out
  out=$("$gs" --backend cpu --n "$N" --steps "$STEPS" --effects friction --precision "$precision" --step "$step")
  echo "$out" | sed -E 's/.*particle_steps_per_s=([^ ]+).*/\1/' | tr '\n' ' '
  echo "$out" | sed -E 's/.*(wall_s=[^ ]+).*/\1/'
}

echo "N=$N steps=$STEPS (after 20 warm-up) dt=$dt s ($step contact times) repeats=$REPEATS liggghts_np=$NP grainstorm=$gs precision=$precision"
(cd "$work" && "$lig" -h -log none 2>/dev/null | grep '^LIGGGHTS' | head -n 1) || true
: > "$work/lig.rates"
: > "$work/gs.rates"
for k in $(seq 1 "$REPEATS"); do
  load=$(cut -d' ' -f1-3 /proc/loadavg)
  r=$(run_liggghts)
  echo "run $k liggghts    load=[$load] particle_steps_per_s=$r"
  echo "${r%% *}" >> "$work/lig.rates"
  load=$(cut -d' ' -f1-3 /proc/loadavg)
  r=$(run_grainstorm)
  echo "run $k grainstorm  load=[$load] particle_steps_per_s=$r"
  echo "${r%% *}" >> "$work/gs.rates"
done

summary() {
  sort -g "$2" | awk -v name="$1" '{v[NR]=$1} END {
    med = (NR % 2) ? v[(NR+1)/2] : (v[NR/2] + v[NR/2+1]) / 2;
    printf "%-11s best %.4g  median %.4g particle-steps/s\n", name, v[NR], med}'
}
summary liggghts "$work/lig.rates"
summary grainstorm "$work/gs.rates"
