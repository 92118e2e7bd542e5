#!/usr/bin/env bash
# Quick start: installs dependencies, builds, and runs the demo scene (a bed
# of 2000 spheres settling in a box) on the GPU when there is one, else on the CPU.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/install_deps.sh"
"$root/tools/build.sh" "$root/build"
backend=cpu
if command -v nvidia-smi >/dev/null && nvidia-smi -L >/dev/null 2>&1 && \
   grep -q "GS_HAVE_CUDA_CACHED:INTERNAL=ON" "$root/build/CMakeCache.txt" 2>/dev/null; then
  backend=cuda
fi
"$root/build/src/grainstorm" check "$root/cases/demo/settle.yaml"
"$root/build/src/grainstorm" run "$root/cases/demo/settle.yaml" --backend "$backend" --out "$root/build/demo_out" --overwrite
echo "quickstart: demo output in $root/build/demo_out"
