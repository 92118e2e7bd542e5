#!/usr/bin/env bash
# The test command: builds the CPU backend and runs the whole suite (unit,
# physics and 2-rank MPI tests through CTest), then builds the CUDA backend
# (compile and link; its tests run where a GPU is present).
#   GS_REQUIRE_CUDA=1  fail when nvcc is missing instead of skipping the CUDA build
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
jobs=${GS_BUILD_JOBS:-$(nproc)}
"$root/tools/build.sh" "$root/build-cpu" -DGS_ENABLE_CUDA=OFF
(cd "$root/build-cpu" && ctest --output-on-failure -j "$jobs")
if command -v nvcc >/dev/null || [[ -x /usr/local/cuda/bin/nvcc ]]; then
  "$root/tools/build.sh" "$root/build-cuda" -DGS_ENABLE_CUDA=ON
  grep -q "GS_HAVE_CUDA_CACHED:INTERNAL=ON" "$root/build-cuda/CMakeCache.txt"
  if command -v nvidia-smi >/dev/null && nvidia-smi -L >/dev/null 2>&1; then
    (cd "$root/build-cuda" && GS_TEST_BACKENDS=cpu,cuda ctest --output-on-failure -j 4)
  else
    echo "test.sh: CUDA backend built (no GPU here: its tests run on a GPU machine)"
  fi
elif [[ ${GS_REQUIRE_CUDA:-0} == 1 ]]; then
  echo "test.sh: nvcc not found but GS_REQUIRE_CUDA=1" >&2
  exit 1
else
  echo "test.sh: nvcc not found, CUDA backend not built"
fi
