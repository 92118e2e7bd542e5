#!/usr/bin/env bash
# What the silo's processes (inlet, outlet) and each kind of measurement cost
# per particle-step on the GPU (bench/process_cost.py says which runs):
#   bench/process_cost.sh BUILD_DIR OUT [extra arguments of process_cost.py, e.g. --backend cpu --variant ci]
# Writes OUT/process_cost.md (the table for docs/PERFORMANCE.md); the runs stay
# in RUNS (default /tmp/process_cost_runs).
set -euo pipefail
build=$(cd "$1" && pwd)
out=$2
shift 2
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
{
  date -u
  nvidia-smi --query-gpu=name --format=csv,noheader 2>/dev/null || true
  git -C "$root" rev-parse --short HEAD 2>/dev/null || true
} > "$out/process_cost.md"
python3 "$root/bench/process_cost.py" "$build/src/grainstorm" "${RUNS:-/tmp/process_cost_runs}" "$@" | tee -a "$out/process_cost.md"
