#!/usr/bin/env bash
# One session on a GPU machine: build with CUDA, run the whole test suite on
# both backends, compare CPU and GPU runs of the demo, then the benchmarks.
# Results go to $OUT (default ./device_out). Usage, from the repository root:
#   [TESTS_REGEX=re] [TESTS_EXCLUDE=re] [BUILD_TARGET=t] bench/device_session.sh [all|tests|bench|baseline|refactor|effects|mixer|mixprofile|mixacc|accuracy|output|scaling][,...]
# BUILD_TARGET builds only that target (e.g. settle_bench) instead of everything.
# METIS and yaml-cpp may be carried as unpacked Debian packages in carry/root
# when the machine lacks them: mkdir -p carry && cd carry && apt-get download
# libmetis5 libmetis-dev libyaml-cpp0.7 libyaml-cpp-dev && for f in *.deb; do
# dpkg -x $f root; done
set -uo pipefail
what=${1:-all}
root=$(pwd)
OUT=${OUT:-$root/device_out}
mkdir -p "$OUT"
source "$root/bench/carried_deps.sh"
use_carried_deps "$root"
log=$OUT/session.log
{
  date -u; nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv; git rev-parse HEAD 2>/dev/null
  git status --short 2>/dev/null | head -20
} > "$log" 2>&1
cmake -S . -B build-gpu -DCMAKE_BUILD_TYPE=Release -DGS_ENABLE_CUDA=ON "${extra[@]}" >> "$log" 2>&1 &&
  cmake --build build-gpu -j 16 ${BUILD_TARGET:+--target $BUILD_TARGET} >> "$log" 2>&1 ||
  { echo "BUILD FAILED" >> "$log"; tail -50 "$log"; exit 1; }
echo "build ok" >> "$log"

wants() { [[ ,$what, == *,all,* || ,$what, == *,$1,* ]]; }

if wants tests; then
  (cd build-gpu && GS_TEST_BACKENDS=cpu,cuda OMP_NUM_THREADS=4 timeout ${TESTS_LIMIT:-400} ctest -j 4 --timeout 300 --output-on-failure ${TESTS_REGEX:+-R "$TESTS_REGEX"} ${TESTS_EXCLUDE:+-E "$TESTS_EXCLUDE"} \
     > "$OUT/ctest_gpu.log" 2>&1)
  tail -25 "$OUT/ctest_gpu.log" >> "$log"
  # CPU against GPU on the demo scene, and 2 ranks sharing the GPU against 1.
  demo=cases/demo/settle.yaml
  g=build-gpu/src/grainstorm
  {
    $g run $demo --backend cpu --out /tmp/demo_cpu --overwrite 2>&1 | tail -3
    $g run $demo --backend cuda --out /tmp/demo_gpu --overwrite 2>&1 | tail -3
    mpirun --allow-run-as-root --oversubscribe -np 2 $g run $demo --backend cuda --out /tmp/demo_gpu2 --overwrite 2>&1 | tail -3
    python3 bench/compare_snapshots.py /tmp/demo_gpu /tmp/demo_gpu2 /tmp/demo_cpu
  } >> "$log" 2>&1
fi

if wants bench; then
  b=build-gpu/bench/settle_bench
  {
    for n in 100000 1000000 4000000 16000000; do $b --backend cuda --n $n --steps 200; done
    for e in none friction rolling cohesion; do $b --backend cuda --n 4000000 --steps 200 --effects $e; done
    $b --backend cuda --n 4000000 --steps 200 --precision fp64
    $b --backend cuda --n 4000000 --steps 200 --model hertz
    OMP_NUM_THREADS=1 $b --backend cpu --n 100000 --steps 50
    OMP_NUM_THREADS=16 $b --backend cpu --n 1000000 --steps 50
  } > "$OUT/bench.log" 2>&1
  cat "$OUT/bench.log" >> "$log"
fi
if wants baseline && [[ -d carry/base ]]; then
  # Before against after in the same lease: the tree at an earlier commit, unpacked into carry/base
  # (mkdir -p carry/base && git archive <commit> | tar -x -C carry/base), built beside build-gpu
  # and timed alternately.
  cmake -S carry/base -B build-base -DCMAKE_BUILD_TYPE=Release -DGS_ENABLE_CUDA=ON "${extra[@]}" >> "$log" 2>&1 &&
    cmake --build build-base -j 16 --target settle_bench >> "$log" 2>&1 || echo "BASE BUILD FAILED" >> "$log"
  {
    for round in 1 2; do
      for b in build-base build-gpu; do
        for args in "--effects friction" "--effects rolling" "--model hertz --effects friction"; do
          echo "== $b round $round: $args"
          $b/bench/settle_bench --backend cuda --n 4000000 --steps 200 $args
        done
      done
    done
  } > "$OUT/baseline.log" 2>&1
  cat "$OUT/baseline.log" >> "$log"
fi

if wants refactor && [[ -d carry/base ]]; then
  # A change that must not change results or speed: the tree at an earlier
  # commit (carry/base, as for baseline) against this one, alternately, at 4e6
  # and 16e6 frictional particles, each run ending with its state digest
  # (the same digests: the same bits on the GPU).
  cmake -S carry/base -B build-base -DCMAKE_BUILD_TYPE=Release -DGS_ENABLE_CUDA=ON "${extra[@]}" >> "$log" 2>&1 &&
    cmake --build build-base -j 16 --target settle_bench >> "$log" 2>&1 || echo "BASE BUILD FAILED" >> "$log"
  {
    for round in 1 2 3; do
      for b in build-base build-gpu; do
        for n in 4000000 16000000; do
          echo "== $b round $round: n $n"
          $b/bench/settle_bench --backend cuda --n $n --steps 200 --effects friction --digest yes
        done
      done
    done
    for b in build-base build-gpu; do
      for args in "--effects rolling" "--model hertz --effects friction" "--effects none --precision fp64"; do
        echo "== $b digest: $args"
        $b/bench/settle_bench --backend cuda --n 1000000 --steps 100 $args --digest yes
      done
    done
  } > "$OUT/refactor.log" 2>&1
  cat "$OUT/refactor.log" >> "$log"
fi

if wants effects; then
  # Only the effects a scene calls for: the same bed, effect by effect, on the GPU and the CPU.
  b=build-gpu/bench/settle_bench
  {
    for e in none friction rolling cohesion; do $b --backend cuda --n 4000000 --steps 200 --effects $e; done
    $b --backend cuda --n 4000000 --steps 200 --mesh impeller
    for e in none friction rolling cohesion; do OMP_NUM_THREADS=16 $b --backend cpu --n 1000000 --steps 30 --effects $e; done
    OMP_NUM_THREADS=16 $b --backend cpu --n 1000000 --steps 30 --mesh impeller
    OMP_NUM_THREADS=1 $b --backend cpu --n 100000 --steps 30
  } > "$OUT/effects.log" 2>&1
  cat "$OUT/effects.log" >> "$log"
fi

if wants mixacc; then
  bench/mixer_accuracy.sh build-gpu cuda /tmp/mixacc > "$OUT/mixer_accuracy_cuda.csv" 2>> "$log"
  cat "$OUT/mixer_accuracy_cuda.csv" >> "$log"
fi

if wants mixprofile; then
  # Where a small mixer's step goes: phase split of case a at rest and of its cheap variant turning.
  for c in "case_a.yaml 30000" "case_a_ci.yaml 20000"; do
    set -- $c
    (cd cases/mixer && "$root/build-gpu/src/grainstorm" run "$1" --backend cuda --steps "$2" --out "/tmp/prof_$1" --overwrite 2>&1 |
       grep -E "particles,|done|time per phase")
  done >> "$log" 2>&1
fi

if wants accuracy; then
  # What accuracy costs in time (docs/ACCURACY.md): the grid on the GPU and on 16 CPU threads.
  for b in cuda cpu; do
    OMP_NUM_THREADS=16 build-gpu/bench/accuracy_study --backend $b > "$OUT/accuracy_$b.csv" 2>> "$log"
  done
  python3 bench/plot_accuracy.py "$OUT/accuracy_cuda.csv" "$OUT/accuracy_plots" > "$OUT/accuracy_tables.md" 2>> "$log"
  python3 bench/plot_accuracy.py "$OUT/accuracy_cpu.csv" "$OUT/accuracy_plots" >> "$OUT/accuracy_tables.md" 2>> "$log"
fi

if wants output; then
  # Snapshot output at 16e6 frictional particles on one GPU: the phase line's "output" is the two snapshots.
  timeout 300 bench/scaling_bed.sh build-gpu weak 16000000 1 100 /tmp/output_bed >> "$log" 2>&1
fi

if wants mixer; then
  bench/mixer_run.sh build-gpu a "${MIXER_LIMIT:-240}" "$OUT/mixer" cuda >> "$log" 2>&1
fi

if wants scaling; then
  gpus=$(nvidia-smi -L | wc -l)
  {
    timeout 200 bench/scaling_bed.sh build-gpu weak 2000000 "$gpus" 300 /tmp/scaling
    timeout 200 bench/scaling_bed.sh build-gpu weak 16000000 "$gpus" 100 /tmp/scaling
    timeout 200 bench/scaling_bed.sh build-gpu strong 32000000 "$gpus" 100 /tmp/scaling
  } > "$OUT/scaling.log" 2>&1
  cat "$OUT/scaling.log" >> "$log"
fi
cat "$log"
