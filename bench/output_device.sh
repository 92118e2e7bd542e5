#!/usr/bin/env bash
# Output speed on one GPU (issue 21, "fast output"), the base against this
# tree, as one command from the repository root:
#   [OUT=dir] [COUNTS="24000000 100000000"] [ROUNDS=1] [OB_N=8000000] bench/output_device.sh [BASE_SRC]
# BASE_SRC (default: carry/base, if present): the source tree before, e.g.
#   mkdir -p carry/base && git archive <base commit> | tar -x -C carry/base
# (carry/ is ignored by git: carry it). Without one, this tree runs alone.
# Builds both with CUDA (grainstorm and output_bench, in parallel), then:
#  1. bench/output_speed.sh for each of COUNTS, this tree and the base one
#     after the other, ROUNDS times: a lattice bed of N spheres, 2 steps, an
#     initial and a final snapshot and a checkpoint at the end (24e6:
#     friction, every snapshot field, a checkpoint with history; 1e8: no
#     friction, the default fields). Bytes written, the run's output phase
#     and GB/s over it, each file's own write time;
#  2. output_bench --n OB_N --backend cuda, each build: the parts of a
#     snapshot and a checkpoint (host copy, history, checksum, file writes)
#     and the run's waits.
# Files go to OUTPUT_SPEED_DIR (default /tmp/output_speed, the local disk;
# the 1e8 run writes about 32 GB, removed after each run). Results in $OUT
# (default ./device_out): session.log (the summary), output_speed_<round>/,
# output_bench.txt, build_*.log. About 12 minutes with one round.
# METIS and yaml-cpp may be carried in carry/root as for bench/device_session.sh.
# A dry run on a machine without a GPU: BACKEND=cpu AFTER_BUILD=build-cpu
# [BEFORE_BUILD=...] COUNTS=2000000 OB_N=1000000 (nothing is built).
set -uo pipefail
root=$(pwd)
OUT=${OUT:-$root/device_out}
counts=${COUNTS:-"24000000 100000000"}
rounds=${ROUNDS:-1}
ob_n=${OB_N:-8000000}
backend=${BACKEND:-cuda}
mkdir -p "$OUT"
log=$OUT/session.log
base=${1:-}
[[ -z $base && -d carry/base ]] && base=carry/base
say() { echo "[$(date -u +%T) +${SECONDS}s] $*" | tee -a "$log"; }

source "$root/bench/carried_deps.sh"
use_carried_deps "$root"
{
  date -u; nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv; nproc; free -g; df -h /tmp
  git rev-parse HEAD 2>/dev/null; git status --short 2>/dev/null | head -20
} > "$log" 2>&1
say "base tree: ${base:-none (this tree alone)}"

after=${AFTER_BUILD:-} before=${BEFORE_BUILD:-}
if [[ -z $after ]]; then
  source "$root/bench/build_pair.sh"
  build_pair build-output "$base" grainstorm output_bench || exit 1
fi
say "builds: ${before:-none} against $after"

# 1. The run's output phase, this tree and the base one after the other.
for round in $(seq 1 "$rounds"); do
  say "output_speed.sh round $round: $counts"
  bench/output_speed.sh "$after" "$OUT/output_speed_$round" "$before" "$backend" "$counts" >> "$log" 2>&1
  say "output_speed.sh exit $?"
done

# 2. The parts of one snapshot and one checkpoint.
dir=${OUTPUT_SPEED_DIR:-/tmp/output_speed}/bench
for b in $after $before; do
  say "output_bench $b --n $ob_n"
  echo "$b: $(timeout 300 "$b/bench/output_bench" --n "$ob_n" --dir "$dir" --backend "$backend" 2>&1 | tail -1)" \
    >> "$OUT/output_bench.txt"
  rm -rf "$dir"
done
cat "$OUT/output_bench.txt" >> "$log"
say "done"
