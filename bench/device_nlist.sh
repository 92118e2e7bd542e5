#!/usr/bin/env bash
# One GPU session for the GPU Verlet list (issue 21), as one command from the
# repository root of the branch:
#   [OUT=dir] [BUDGET_S=540] bench/device_nlist.sh [BASE_SRC]
# BASE_SRC (default: carry/base, else base_src): the source tree before the
# change (the merge base: git archive <commit> | tar -x -C carry/base). Without
# one, the benchmarks run this tree alone.
# It builds both trees with CUDA side by side (the base: the command and
# settle_bench only), then, each phase cut to what the budget leaves:
#  1. the CPU-against-GPU comparison: the BackendAgreement test, the Verlet
#     list tests on both backends, and the demo scene on the CPU, on the GPU
#     and on 2 ranks sharing the GPU (bench/compare_snapshots.py);
#  2. the CUDA test suite (GS_TEST_BACKENDS=cuda);
#  3. bench/gpu_bench.sh, base against this tree;
#  4. settle_bench's contact-force line, base against this tree.
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

if [[ -d carry/root/usr ]]; then
  export CMAKE_PREFIX_PATH=$root/carry/root/usr
  export LD_LIBRARY_PATH=$root/carry/root/usr/lib/x86_64-linux-gnu:${LD_LIBRARY_PATH:-}
  extra=(-DMETIS_INCLUDE_DIR=$root/carry/root/usr/include
         -DMETIS_LIBRARY=$root/carry/root/usr/lib/x86_64-linux-gnu/libmetis.so)
else
  extra=()
fi
export PATH=/usr/local/cuda/bin:$PATH
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

# 2. The CUDA test suite (the MPI, CLI and mixer tests run the CPU backend: left out).
tests_s=$(( $(left) > 360 ? 120 : $(left) / 3 ))
say "CUDA test suite (at most ${tests_s} s)"
(cd build-nlist && GS_TEST_BACKENDS=cuda OMP_NUM_THREADS=2 timeout "$tests_s" ctest -j 8 --timeout 100 \
   --output-on-failure -E "mpi|Mpi|MPI|cli|Cli|mixer|Mixer" > "$OUT/ctest_cuda.log" 2>&1)
say "ctest exit $?"
grep -E "tests passed|tests failed|Failed|\(Timeout\)|\*\*\*" "$OUT/ctest_cuda.log" | tail -25 | tee -a "$log"

# 3. The four benchmarks, base against this tree.
before=build-nlist
if [[ -n $base ]]; then
  if wait "$base_pid"; then before=build-base; else say "BASE BUILD FAILED: this tree alone"; tail -20 "$OUT/build_base.log" >> "$log"; fi
fi
bench_s=$(( $(left) - 50 ))
say "benchmarks: $before against build-nlist (at most ${bench_s} s)"
bench/gpu_bench.sh "$before" build-nlist "$OUT/bench" "$bench_s" "${SIZES:-4000000 16000000 64000000}" >> "$log" 2>&1

# 4. settle_bench's contact-force line (its bed, 50 steps: about six contacts per sphere).
say "settle_bench"
for round in 1 2; do
  for b in "$before" build-nlist; do
    for args in "--effects friction" "--effects none"; do
      (($(left) > 8)) || break 3
      echo "== $b round $round: $args" >> "$OUT/settle_bench.log"
      timeout "$(left)" $b/bench/settle_bench --backend cuda --n 4000000 --steps 50 $args >> "$OUT/settle_bench.log" 2>&1
    done
  done
done
cat "$OUT/settle_bench.log" >> "$log"
say "done"
