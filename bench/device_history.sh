#!/usr/bin/env bash
# One GPU session for the contact history's size (issue 21: bytes per
# particle, and the dense bed's speed), base against this tree, as one
# command from the repository root:
#   [OUT=dir] [BUDGET_S=540] [N=4000000] bench/device_history.sh [BASE_SRC]
# BASE_SRC (default: carry/base): the source tree before the change, e.g.
#   mkdir -p carry/base && git archive $(git merge-base HEAD main) | tar -x -C carry/base
# (carry/ is ignored by git: carry it). Without one, this tree runs against
# itself. The base must digest as this tree does (src/io/state_digest.cpp:
# contacts by partner id, since 789e1ea), or the digests below differ for
# that reason alone.
# Both trees are built with CUDA (the command and settle_bench only), then:
#  1. bench/memory_bench.sh this base: the exact peak and held bytes per
#     particle of settle_bench's bed and of the static dense lattice (six
#     neighbours, walls at its faces), friction and none, with both builds'
#     state digests (which must agree), and the largest frictional bed;
#  2. settle_bench --n N --steps 200, friction and none, base and this tree
#     alternated, ROUNDS rounds (default 2): particle-steps/s, peak bytes per
#     particle, contacts per particle, forces and neighbour seconds;
#  3. bench/gpu_bench.sh, the dense static bed only (N, friction and none):
#     particle-steps/s of the step loop, bytes and contacts per particle.
# Everything goes to $OUT (default ./device_out): session.log (the summary),
# build_*.log, memory/, settle_bench.log, bench/.
# METIS and yaml-cpp may be carried in carry/root as for bench/device_session.sh.
# A dry run on a machine without a GPU: BACKEND=cpu with BEFORE_BUILD and
# AFTER_BUILD (existing CPU builds; nothing is built), small N and LARGEST
# (memory_bench's default, 4e8 spheres, would exhaust the host's memory), e.g.
#   BACKEND=cpu N=8000 LARGEST=4000:12 BEFORE_BUILD=build AFTER_BUILD=build bench/device_history.sh
set -uo pipefail
root=$(pwd)
OUT=${OUT:-$root/device_out}
budget=${BUDGET_S:-540}
n=${N:-4000000}
rounds=${ROUNDS:-2}
backend=${BACKEND:-cuda}
mkdir -p "$OUT"
log=$OUT/session.log
base=${1:-}
[[ -z $base && -d carry/base ]] && base=carry/base
say() { echo "[$(date -u +%T) +${SECONDS}s] $*" | tee -a "$log"; }
left() { echo $((budget - SECONDS)); }

source "$root/bench/carried_deps.sh"
use_carried_deps "$root"
{
  date -u; nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv; nproc
  git rev-parse HEAD 2>/dev/null; git status --short 2>/dev/null | head -20
} > "$log" 2>&1
say "base tree: ${base:-none (this tree against itself)}"

after=${AFTER_BUILD:-} before=${BEFORE_BUILD:-}
if [[ -z $after ]]; then
  source "$root/bench/build_pair.sh"
  build_pair build-history "$base" grainstorm settle_bench || exit 1
fi
before=${before:-$after}  # no base: this tree against itself
say "builds: $before against $after"

# 1. Bytes per particle, exact, and the digests of both builds.
say "memory_bench (N = $n)"
OUT=$OUT/memory N=$n BACKEND=$backend BUDGET_S=$(( $(left) / 3 )) timeout $(( $(left) / 3 + 30 )) \
  bench/memory_bench.sh "$after" "$([[ $before != "$after" ]] && echo "$before")" >> "$log" 2>&1
say "memory_bench exit $?"

# 2. settle_bench, alternated.
say "settle_bench (N = $n, 200 steps, $rounds rounds)"
for round in $(seq 1 "$rounds"); do
  for effects in friction none; do
    for b in "$before" "$after"; do
      (($(left) > 60)) || break 3
      echo "== round $round, $b, --effects $effects" >> "$OUT/settle_bench.log"
      timeout 120 "$b/bench/settle_bench" --backend "$backend" --n "$n" --steps 200 --effects "$effects" --digest yes \
        >> "$OUT/settle_bench.log" 2>&1
    done
  done
done
grep -E "^==|particle_steps_per_s|state_digest" "$OUT/settle_bench.log" >> "$log"

# 3. The dense static bed's step loop.
bench_s=$(( $(left) - 20 ))
say "gpu_bench, dense bed only (at most ${bench_s} s)"
SKIP="random mixer_b mixer_a dense_2ranks" BACKEND=$backend bench/gpu_bench.sh "$before" "$after" "$OUT/bench" "$bench_s" "$n" \
  >> "$log" 2>&1
say "done"
