#!/usr/bin/env bash
# Small scenes on one GPU (issue 21: "fewer, fused launches and no host
# synchronisation inside a step"), two builds side by side; builds nothing:
#   [OUT=dir] [MIXER_STEPS=3000] [BED_N=100000] [BED_STEPS=2000] [ROUNDS=2] \
#     bench/small_scene.sh BUILD BASE_BUILD
# BUILD and BASE_BUILD are CUDA build directories (src/grainstorm; for the bed
# also bench/settle_bench). Run from anywhere; the scenes come from this tree.
#  1. Mixer case a, soft variant (cases/mixer/case_a_soft.yaml, Table 4's
#     stiffnesses x 0.01): each build settles it to step SETTLE_STEPS (24000,
#     t = 1.02 s: the impeller turns from t = 1 s) and checkpoints; each then
#     restarts from its own checkpoint (checkpoint formats differ between
#     commits) for MIXER_STEPS steps, ROUNDS times, alternated. Microseconds per step from the run log's stepping
#     time (the phases' sum: set-up and output left out), particle-steps/s from it.
#  2. A 1e5-particle bed: settle_bench (a lattice pressed 0.5 % into overlap,
#     frictional, fp32 forces, settling and loosening as it runs) with each
#     build: its wall time per step and particle-steps/s.
#  3. A CUDA timeline of PROFILE_STEPS mixer steps from each build's
#     checkpoint (bench/gpu_trace.sh, a CUPTI tracer, and
#     bench/gpu_timeline.py): per step the kernels, the device's idle gaps
#     and the host's API calls, over the second half of the steps.
# Everything goes to $OUT (default ./small_scene_out): summary.txt, logs,
# the traces and their timelines.
set -uo pipefail
if (($# != 2)); then
  echo "usage: [OUT=dir] bench/small_scene.sh BUILD BASE_BUILD" >&2
  exit 2
fi
build=$(cd "$1" && pwd) || exit 2
base=$(cd "$2" && pwd) || exit 2
root=$(cd "$(dirname "$0")/.." && pwd)
OUT=${OUT:-$(pwd)/small_scene_out}
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
settle_steps=${SETTLE_STEPS:-24000}
mixer_steps=${MIXER_STEPS:-3000}
bed_n=${BED_N:-100000}
bed_steps=${BED_STEPS:-2000}
rounds=${ROUNDS:-2}
profile_steps=${PROFILE_STEPS:-1000}
backend=${BACKEND:-cuda}  # cpu: a smoke test of this script where there is no GPU
summary=$OUT/summary.txt
say() { echo "$*" | tee -a "$summary"; }
: > "$summary"
{
  date -u
  nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>/dev/null
  echo "BUILD=$build BASE_BUILD=$base"
  git -C "$root" rev-parse HEAD 2>/dev/null
} >> "$summary"

mixer_dir=$root/cases/mixer
scene=case_a_soft.yaml
particles=7680
work=$OUT/work
mkdir -p "$work"

# Stepping microseconds per step from a run log: the phases' sum (integration,
# neighbour build, contact forces, exchange) over the steps run.
stepping_us() {  # LOG STEPS
  sed -n 's/^time per phase (s, rank 0): integration \([0-9.e+-]*\), neighbour build \([0-9.e+-]*\), contact forces \([0-9.e+-]*\), exchange \([0-9.e+-]*\),.*/\1 \2 \3 \4/p' "$1" |
    awk -v steps="$2" '{ printf "%.1f", ($1 + $2 + $3 + $4) / steps * 1e6 }'
}

# 1. Mixer case a (soft). Each build settles it and restarts from its own
# checkpoint (a build reads only its own checkpoint format).
say "== mixer case a (soft), $particles spheres and the impeller mesh, turning"
end=$((settle_steps + mixer_steps))
for label in base new; do
  b=$build; [[ $label == base ]] && b=$base
  (cd "$mixer_dir" && "$b/src/grainstorm" run "$scene" --backend "$backend" --steps "$settle_steps" \
     --out "$work/settle_$label" --overwrite > "$OUT/mixer_settle_$label.log" 2>&1)
done
for round in $(seq 1 "$rounds"); do
  for label in base new; do
    b=$build; [[ $label == base ]] && b=$base
    log=$OUT/mixer_${label}_$round.log
    checkpoint=$(ls "$work/settle_$label"/checkpoint_*.h5 2>/dev/null | tail -1)
    if [[ -z $checkpoint ]]; then
      say "mixer $label: the settling run left no checkpoint (mixer_settle_$label.log)"; continue
    fi
    rm -rf "$work/mixer_$label"  # a restart writes into a fresh directory (no --overwrite with --restart)
    (cd "$mixer_dir" && "$b/src/grainstorm" run "$scene" --backend "$backend" --restart "$checkpoint" --steps "$end" \
       --out "$work/mixer_$label" > "$log" 2>&1)
    us=$(stepping_us "$log" "$mixer_steps")
    if [[ -z $us ]]; then
      say "mixer $label round $round: failed ($log)"; tail -3 "$log" | tee -a "$summary"; continue
    fi
    rate=$(awk -v us="$us" -v n="$particles" 'BEGIN { printf "%.3g", n / (us * 1e-6) }')
    builds=$(sed -n 's/^neighbour lists built \([0-9]*\) times.*/\1/p' "$log")
    say "mixer $label round $round: $us us/step, $rate particle-steps/s${builds:+, lists built $builds times}"
  done
done

# 2. The 1e5-particle bed.
say "== settling bed, $bed_n spheres, friction, fp32 forces, $bed_steps steps"
for round in $(seq 1 "$rounds"); do
  for label in base new; do
    b=$build; [[ $label == base ]] && b=$base
    line=$("$b/bench/settle_bench" --backend "$backend" --n "$bed_n" --steps "$bed_steps" --effects friction \
             --precision fp32 2>&1 | tee "$OUT/bed_${label}_$round.log" | grep particle_steps_per_s)
    if [[ -z $line ]]; then
      say "bed $label round $round: failed (bed_${label}_$round.log)"; continue
    fi
    wall=$(sed -n 's/.*wall_s=\([0-9.e+-]*\).*/\1/p' <<< "$line")
    rate=$(sed -n 's/.*particle_steps_per_s=\([0-9.e+-]*\).*/\1/p' <<< "$line")
    n=$(sed -n 's/.* n=\([0-9]*\).*/\1/p' <<< "$line")
    us=$(awk -v w="$wall" -v s="$bed_steps" 'BEGIN { printf "%.1f", w / s * 1e6 }')
    say "bed $label round $round: n=$n, $us us/step, $rate particle-steps/s"
  done
done

# 3. A CUDA timeline of the mixer's steps with each build (bench/gpu_trace.sh,
# CUPTI; Nsight Systems is not on every GPU machine): per step the kernels,
# the device's idle gaps and the host's API calls, and one rebuild step in order.
if [[ $backend != cuda ]]; then
  exit 0
fi
say "== CUDA timeline of $profile_steps mixer steps (bench/gpu_trace.sh, bench/gpu_timeline.py)"
for label in base new; do
  b=$build; [[ $label == base ]] && b=$base
  checkpoint=$(ls "$work/settle_$label"/checkpoint_*.h5 2>/dev/null | tail -1)
  [[ -n $checkpoint ]] || { say "$label: no mixer checkpoint: no timeline"; continue; }
  rm -rf "$work/trace_$label"
  (cd "$mixer_dir" && TRACE="$OUT/trace_$label.csv" "$root/bench/gpu_trace.sh" "$b/src/grainstorm" run "$scene" \
     --backend cuda --restart "$checkpoint" --steps $((settle_steps + profile_steps)) --out "$work/trace_$label" \
     > "$OUT/trace_$label.log" 2>&1)
  python3 "$root/bench/gpu_timeline.py" "$OUT/trace_$label.csv" --detail ListPass > "$OUT/timeline_$label.txt" 2>&1
  say "$label: $(head -1 "$OUT/timeline_$label.txt") (timeline_$label.txt)"
done
