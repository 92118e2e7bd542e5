#!/usr/bin/env bash
# What the silo's processes (inlet, outlet) and each kind of measurement cost
# per particle-step on the GPU (issue 20, "Cost"; bench/process_cost.py says
# which runs): nine runs of the full silo (46 d wide, ~106k spheres, D0 =
# 10 d), one after the other, each 0.5 s simulated (29,800 steps of 16.8 us:
# 0.3 s settling behind the gate, 0.2 s of discharge), ~3.2e9 particle-steps a run.
#   [BUDGET_S=170] bench/process_cost.sh BUILD_DIR OUT [extra arguments of process_cost.py, e.g. --backend cpu --variant smoke]
# Estimate (not measured: no GPU where this was written): on one H200 a
# scene of this size steps at ~0.4-0.6 ms (docs/PERFORMANCE.md: 76.8k
# spheres, 0.49 ms), so 12-18 s a run with its set-up and about 2-2.7
# minutes for the nine; a run that would end past BUDGET_S (judged by the
# longest so far) is skipped and named in the table. CPU check of the script:
#   bench/process_cost.sh build-cpu /tmp/pc --backend cpu --variant smoke --d0 5 --settle 0.2 --discharge 0.1
# Writes OUT/process_cost.md (machine, commit, the table for docs/PERFORMANCE.md);
# the runs stay in RUNS (default /tmp/process_cost_runs).
set -uo pipefail
build=$(cd "$1" && pwd)
out=$2
shift 2
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
{
  echo "date: $(date -u '+%Y-%m-%d %H:%M:%S UTC')"
  echo "machine: $(nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>/dev/null | head -1 || echo 'no nvidia-smi'), $(nproc) cores"
  echo "commit: $(git -C "$root" rev-parse --short HEAD 2>/dev/null)"
  echo
} > "$out/process_cost.md"
python3 "$root/bench/process_cost.py" "$build/src/grainstorm" "${RUNS:-/tmp/process_cost_runs}" \
  --budget-s "${BUDGET_S:-170}" "$@" | tee -a "$out/process_cost.md"
exit "${PIPESTATUS[0]}"
