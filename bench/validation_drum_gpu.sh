#!/usr/bin/env bash
# Rotating drum at full size on the GPU (docs/VALIDATION.md, "Rotating drum"):
# tools/drum.py --variant full, all cases at once on the one GPU (each case is
# a small bed, so one alone leaves the GPU idle between launches), then the
# table, the run lines and the plots under OUT.
#   bench/validation_drum_gpu.sh BUILD_DIR OUT [BACKEND]     (from the repository root)
# Writes OUT/drum_table.md (the table, the checks' inputs, each run's
# particle-steps/s), OUT/drum_angle_<backend>.png (angle against Fr and
# against rolling friction), OUT/drum_sections_<backend>.png (each case's last
# cross-section), OUT/drum_env.txt, and OUT/runs/<backend>/*.yaml, run.log and
# timeseries.csv of every case (the snapshots are deleted once measured).
# Sized for about 3 minutes on one H200: 15 cases of about 13,500 spheres;
# JOBS (default 15) sets how many run at once.
set -uo pipefail
build=${1:?usage: $0 BUILD_DIR OUT [BACKEND]} out=${2:?usage: $0 BUILD_DIR OUT [BACKEND]} backend=${3:-cuda}
mkdir -p "$out"
{
  date -u
  nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv 2>&1
  git rev-parse HEAD 2>/dev/null
  python3 -c "import matplotlib; print('matplotlib', matplotlib.__version__)" 2>&1
} > "$out/drum_env.txt"
start=$(date +%s)
OMP_NUM_THREADS=1 python3 tools/drum.py "$build/src/grainstorm" --variant full --backends "$backend" \
  --jobs "${JOBS:-15}" --keep "$out/runs" --prune --plots "$out" > "$out/drum_table.md" 2> "$out/drum.log"
rc=$?
echo "tools/drum.py --variant full: exit $rc after $(($(date +%s) - start)) s" | tee -a "$out/drum_table.md"
cat "$out/drum_table.md"
exit $rc
