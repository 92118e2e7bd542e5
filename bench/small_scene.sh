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
#  3. Where nsys is on PATH: the mixer restart profiled (CUDA API trace) for
#     PROFILE_STEPS and twice as many steps with each build; the difference
#     of the two, per step, for the synchronising calls and launches
#     (cudaDeviceSynchronize, cudaStreamSynchronize, cudaEventSynchronize,
#     cudaMemcpy, cudaMemcpyAsync, cudaLaunchKernel), so set-up drops out.
# Everything goes to $OUT (default ./small_scene_out): summary.txt, logs, nsys
# reports and their cuda_api_sum CSVs.
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

# 3. CUDA API calls per step (nsys).
if ! command -v nsys > /dev/null; then
  say "nsys not on PATH: no API counts"
  exit 0
fi
if ! ls "$work"/settle_base/checkpoint_*.h5 "$work"/settle_new/checkpoint_*.h5 > /dev/null 2>&1; then
  say "no mixer checkpoints: no API counts"
  exit 0
fi
say "== CUDA API calls per mixer step (nsys, difference of $profile_steps and $((2 * profile_steps)) steps)"
api_csv() {  # LABEL BUILD STEPS -> the cuda_api_sum CSV's path
  local name=$OUT/nsys_${1}_$3 checkpoint
  checkpoint=$(ls "$work/settle_$1"/checkpoint_*.h5 | tail -1)
  rm -rf "$work/nsys_$1"
  (cd "$mixer_dir" && nsys profile --trace=cuda --sample=none --cpuctxsw=none --force-overwrite=true -o "$name" \
     "$2/src/grainstorm" run "$scene" --backend "$backend" --restart "$checkpoint" --steps $((settle_steps + $3)) \
     --out "$work/nsys_$1" > "$name.log" 2>&1)
  # The report's name changed between nsys versions.
  nsys stats --report cuda_api_sum --format csv --force-export=true --output "$name" "$name.nsys-rep" \
    > /dev/null 2>&1 ||
    nsys stats --report cudaapisum --format csv --force-export=true --output "$name" "$name.nsys-rep" > /dev/null 2>&1
  ls "$name"_*api*sum*.csv 2>/dev/null | head -1
}
for label in base new; do
  b=$build; [[ $label == base ]] && b=$base
  short=$(api_csv "$label" "$b" "$profile_steps")
  long=$(api_csv "$label" "$b" $((2 * profile_steps)))
  if [[ -z $short || -z $long ]]; then
    say "$label: nsys gave no API summary (see $OUT/nsys_${label}_*.log)"; continue
  fi
  python3 - "$short" "$long" "$profile_steps" "$label" <<'PY' | tee -a "$summary"
import csv, sys
short, long, steps, label = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
def calls(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    out = {}
    for r in rows:
        name = r.get("Name", "")
        count = r.get("Num Calls", r.get("Calls", "0"))
        out[name.split("_v")[0]] = out.get(name.split("_v")[0], 0) + int(count.replace(",", ""))
    return out
a, b = calls(short), calls(long)
names = ["cudaDeviceSynchronize", "cudaStreamSynchronize", "cudaEventSynchronize", "cudaMemcpy",
         "cudaMemcpyAsync", "cudaMemsetAsync", "cudaMemset", "cudaLaunchKernel", "cudaEventRecord"]
print(label + ": per step: " + ", ".join(f"{n} {(b.get(n, 0) - a.get(n, 0)) / steps:.3f}" for n in names))
PY
done
