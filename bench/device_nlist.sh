#!/usr/bin/env bash
# One GPU session for the GPU Verlet list (issue 21), as one command from the
# repository root of the branch:
#   [OUT=dir] [BUDGET_S=540] bench/device_nlist.sh [BASE_SRC]
# BASE_SRC (default: carry/base, else base_src): the source tree before the
# change, unpacked before the tree is copied to the GPU machine, e.g.
#   mkdir -p carry/base && git archive $(git merge-base HEAD main) | tar -x -C carry/base
# (carry/ is ignored by git: carry it). Without one, the benchmarks run this
# tree against itself.
# It builds both trees with CUDA side by side (the base: the command and
# settle_bench only), then, each phase cut to what the budget leaves:
#  1. the CPU-against-GPU comparison: the BackendAgreement test, the Verlet
#     list tests on both backends, and the demo scene on the CPU, on the GPU
#     and on 2 ranks sharing the GPU (bench/compare_snapshots.py);
#  2. the test suite with GS_TEST_BACKENDS=cuda (at most TESTS_S s, 200);
#  3. bench/gpu_bench.sh, base against this tree, with what is left;
#  4. settle_bench, base against this tree (when time is left).
# Everything goes to $OUT (default ./device_out): session.log (the summary),
# build_*.log, agreement.log, ctest_cuda.log, bench/ (gpu_bench.md, CSV, logs).
# METIS and yaml-cpp may be carried in carry/root as for bench/device_session.sh.
set -uo pipefail
root=$(pwd)
OUT=${OUT:-$root/device_out}
budget=${BUDGET_S:-540}
mkdir -p "$OUT"
log=$OUT/session.log
base=${1:-}
[[ -z $base && -d carry/base ]] && base=carry/base
[[ -z $base && -d base_src ]] && base=base_src
say() { echo "[$(date -u +%T) +${SECONDS}s] $*" | tee -a "$log"; }
left() { echo $((budget - SECONDS)); }

source "$root/bench/carried_deps.sh"
use_carried_deps "$root"
{
  date -u; nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv; nproc
  git rev-parse HEAD 2>/dev/null; git status --short 2>/dev/null | head -20
} > "$log" 2>&1
say "base tree: ${base:-none}"

# Both builds at once: this tree in full (its tests), the base's command and benchmark only.
cores=$(nproc)
( cmake -S . -B build-nlist -DCMAKE_BUILD_TYPE=Release -DGS_ENABLE_CUDA=ON "${extra[@]}" &&
  cmake --build build-nlist -j "$cores" ) > "$OUT/build_nlist.log" 2>&1 &
after_pid=$!
if [[ -n $base ]]; then
  ( cmake -S "$base" -B build-base -DCMAKE_BUILD_TYPE=Release -DGS_ENABLE_CUDA=ON "${extra[@]}" &&
    cmake --build build-base -j "$((cores / 2))" --target grainstorm settle_bench ) > "$OUT/build_base.log" 2>&1 &
  base_pid=$!
fi
if ! wait $after_pid; then
  say "BUILD FAILED (build_nlist.log):"; tail -40 "$OUT/build_nlist.log" | tee -a "$log"; exit 1
fi
say "build ok"

# 1. CPU against GPU.
say "agreement"
(cd build-nlist && GS_TEST_BACKENDS=cpu,cuda OMP_NUM_THREADS=8 timeout 120 ctest -V \
   -R "BackendAgreement|VerletList" > "$OUT/agreement.log" 2>&1)
grep -E "tests passed|Failed|FAILED|\*\*\*|largest CPU-GPU" "$OUT/agreement.log" | tee -a "$log"
g=build-nlist/src/grainstorm
demo=cases/demo/settle.yaml
{
  OMP_NUM_THREADS=8 timeout 60 $g run $demo --backend cpu --out /tmp/nlist_demo_cpu --overwrite 2>&1 | grep -E "done|peak"
  timeout 60 $g run $demo --backend cuda --out /tmp/nlist_demo_gpu --overwrite 2>&1 | grep -E "done|peak"
  timeout 60 mpirun --allow-run-as-root --oversubscribe -np 2 $g run $demo --backend cuda --out /tmp/nlist_demo_gpu2 \
    --overwrite 2>&1 | grep -E "done|peak"
  python3 bench/compare_snapshots.py /tmp/nlist_demo_gpu /tmp/nlist_demo_gpu2 /tmp/nlist_demo_cpu
} >> "$OUT/agreement.log" 2>&1
tail -5 "$OUT/agreement.log" | tee -a "$log"

# 2. The test suite with GS_TEST_BACKENDS=cuda (less the slow mixer run on
# CPU ranks): up to TESTS_S seconds (default 200; 399 tests took about 280 s
# at ctest -j 8 on an H200 host), at most half of what is left.
tests_s=${TESTS_S:-200}
(( tests_s > $(left) / 2 )) && tests_s=$(( $(left) / 2 ))
say "test suite on cuda (at most ${tests_s} s)"
(cd build-nlist && GS_TEST_BACKENDS=cuda OMP_NUM_THREADS=2 timeout "$tests_s" ctest -j 16 --timeout 100 \
   --output-on-failure -E "^mixer_case_a" > "$OUT/ctest_cuda.log" 2>&1)
say "ctest exit $? (124: cut by the budget)"
grep -E "tests passed|tests failed|Failed|\(Timeout\)|\*\*\*|^ *[0-9]+/[0-9]+ Test" "$OUT/ctest_cuda.log" | tail -3 | tee -a "$log"
grep -E "\*\*\*Failed|\(Failed\)|\(Timeout\)" "$OUT/ctest_cuda.log" | tee -a "$log"

# 3. The four benchmarks, base against this tree.
before=build-nlist
if [[ -n $base ]]; then
  if wait "$base_pid"; then before=build-base; else say "BASE BUILD FAILED: this tree alone"; tail -20 "$OUT/build_base.log" >> "$log"; fi
fi
bench_s=$(( $(left) - 20 ))
say "benchmarks: $before against build-nlist (at most ${bench_s} s)"
bench/gpu_bench.sh "$before" build-nlist "$OUT/bench" "$bench_s" "${SIZES:-4000000 16000000 64000000}" >> "$log" 2>&1

# 4. settle_bench's line (its bed, 50 steps: about six contacts per sphere, expanding).
say "settle_bench"
for args in "$before --effects friction" "build-nlist --effects friction" "$before --effects none" \
            "build-nlist --effects none"; do
  (($(left) > 4)) || break
  set -- $args
  b=$1; shift
  echo "== $b: $*" >> "$OUT/settle_bench.log"
  timeout $(left) $b/bench/settle_bench --backend cuda --n 4000000 --steps 50 "$@" >> "$OUT/settle_bench.log" 2>&1
done
cat "$OUT/settle_bench.log" >> "$log"
say "done"
