#!/usr/bin/env bash
# Configures and builds grainstorm into BUILD_DIR (default build/).
#   tools/build.sh [BUILD_DIR] [extra cmake args...]
# The CUDA backend is built when nvcc is found on PATH or in /usr/local/cuda.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
shift || true
if ! command -v nvcc >/dev/null && [[ -x /usr/local/cuda/bin/nvcc ]]; then
  export PATH=/usr/local/cuda/bin:$PATH
fi
jobs=${GS_BUILD_JOBS:-$(nproc)}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build "$build" -j "$jobs"
