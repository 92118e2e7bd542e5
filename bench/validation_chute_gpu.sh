#!/usr/bin/env bash
# Inclined chute flow on a rough base at full size on the GPU (docs/VALIDATION.md,
# "Inclined chute flow"; Silbert et al., Phys. Rev. E 64, 051302, 2001): the
# `full` preset of tools/chute_flow.py (Silbert's stiffness k_n = 2e5 m g / d,
# H = 20 d on 40 d x 20 d, seven angles 20-26 deg and one at 14 deg, run JOBS
# at a time on the one GPU, then four steps of bisection of the flow/no-flow angle).
# Writes under OUT: chute_summary.md, chute_profiles.csv, chute_energy.csv,
# the plots chute_profiles.png and chute_energy.png (when matplotlib is there),
# the runs' scenes and measurement logs (runs/), and run.log with the date,
# the GPU and the commit.
#   bench/validation_chute_gpu.sh BUILD OUT [JOBS=4]
# BUILD holds a CUDA build (BUILD/src/grainstorm). 16,960 particles per run
# (16,000 flowing on 960 frozen), 4.0e5 steps each (100 tau at dt = t_c / 20):
# 6.8e9 particle-steps per run, 8.2e10 for the 12 runs, about 1.5 minutes at
# 1e9 particle-steps/s (a run this small may not fill the GPU: JOBS runs share
# it). CHUTE_PRESET=medium runs the CPU preset instead.
set -euo pipefail
build=$(cd "$1" && pwd)
out=$(mkdir -p "$2" && cd "$2" && pwd)
jobs=${3:-4}
root=$(cd "$(dirname "$0")/.." && pwd)
binary=$build/src/grainstorm
[[ -x $binary ]] || { echo "no grainstorm in $build/src" >&2; exit 2; }
python=python3
for candidate in /usr/bin/python3 python3; do
  if command -v "$candidate" >/dev/null && "$candidate" -c "import matplotlib" 2>/dev/null; then python=$candidate; break; fi
done
{
  date -u
  nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv 2>/dev/null || echo "no nvidia-smi"
  (cd "$root" && git rev-parse HEAD 2>/dev/null) || true
} > "$out/run.log"
start=$(date +%s)
MPLBACKEND=Agg "$python" "$root/tools/chute_flow.py" "$binary" --preset "${CHUTE_PRESET:-full}" --backend cuda \
  --jobs "$jobs" --out "$out" --work "$out/runs" 2>&1 | tee -a "$out/run.log"
echo "wall: $(( $(date +%s) - start )) s" | tee -a "$out/run.log"
