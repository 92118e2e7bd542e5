#!/usr/bin/env bash
# The exchange's share of a step on two ranks, before and after the halo was
# kept between rebuilds (docs/MULTI_RANK.md, "What moves when"): a settling
# lattice bed of N spheres per rank (bench/lattice_bed.sh) stacked along z,
# the slab axis, run by BUILD and, when given, by BASE_BUILD (a build of the
# commit before, built beside it from
# `mkdir -p carry/base && git archive <commit> | tar -x -C carry/base`).
# Prints per build the phases' seconds per step from the run log
# ("time per phase", whose sum is the run's time per step: a halo or list
# rebuild is timed each time, the rest of each phase on every 128th step and
# scaled to the rest of the run's time), the exchange's
# share of the step, and the halo's rebuilds; the logs stay in OUT. A timed
# step waits for the device between its phases, so the exchange's figure is
# what the exchange costs where nothing hides it; what the overlap with the
# forces gains shows in the step's time.
#   [N=16000000] [STEPS=300] [BACKEND=cuda] [RANKS=2] [EXCHANGE=host] [ROUNDS=1] \
#     bench/exchange_share.sh BUILD OUT [BASE_BUILD]
# BACKEND=cuda runs every rank on GPU 0 (ranks sharing one GPU move their
# messages through host buffers, EXCHANGE=host); BACKEND=cpu runs CPU ranks
# with OMP_NUM_THREADS=${THREADS:-1} each.
set -euo pipefail
build=$(cd "$1" && pwd) out=$2 base=${3:-}
n=${N:-16000000} steps=${STEPS:-300} backend=${BACKEND:-cuda} ranks=${RANKS:-2} exchange=${EXCHANGE:-host}
[[ -n $base ]] && base=$(cd "$base" && pwd)
mkdir -p "$out"
out=$(cd "$out" && pwd)
py() { python3 -c "print($1)"; }
side=$(py "round(($n) ** (1/3))")
layers=$((side * ranks))
"$(dirname "$0")/lattice_bed.sh" "$side" "$layers" "$out/run" > "$out/bed.yaml"
echo "bed: $side x $side x $layers spheres ($(py "$side * $side * $side") per rank), $ranks $backend ranks, $steps steps"
[[ $backend == cuda ]] && export CUDA_VISIBLE_DEVICES=${CUDA_VISIBLE_DEVICES:-0}
export OMP_NUM_THREADS=${THREADS:-1}

# Seconds per step of each phase, and the exchange's share, from a run log.
share() {
  python3 - "$1" "$steps" <<'PY'
import re, sys
log, steps = open(sys.argv[1]).read(), int(sys.argv[2])
m = re.search(r"integration ([\d.]+), neighbour build ([\d.]+), contact forces ([\d.]+), exchange ([\d.]+)", log)
if not m:
    sys.exit("no phase timings in " + sys.argv[1])
i, nb, f, x = map(float, m.groups())
step = i + nb + f + x
print(f"  per step: integration {1e3*i/steps:.2f} ms, neighbours {1e3*nb/steps:.2f} ms, forces {1e3*f/steps:.2f} ms, "
      f"exchange {1e3*x/steps:.2f} ms; exchange share {100*x/step:.1f} % of {1e3*step/steps:.2f} ms")
for line in log.splitlines():
    if "exchange split" in line:
        print("  " + line.split(": ", 1)[1] if ": " in line else line)
PY
}

run() {  # run LABEL BUILD
  local log=$out/$1.log
  rm -rf "$out/run"
  mpirun --allow-run-as-root --oversubscribe -np "$ranks" --bind-to none "$2/src/grainstorm" run "$out/bed.yaml" \
    --backend "$backend" --exchange "$exchange" --steps "$steps" --overwrite > "$log" 2>&1 ||
    { echo "$1: run failed"; tail -5 "$log"; return 1; }
  echo "$1 ($2):"
  share "$log"
}

# ROUNDS alternated: two ranks sharing a GPU take turns on it by time slices,
# and one run of a build differs from the next by a third (docs/PERFORMANCE.md).
for r in $(seq 1 "${ROUNDS:-1}"); do
  [[ -n $base ]] && run "before$r" "$base"
  run "after$r" "$build"
done
