#!/usr/bin/env bash
# The silo validation at full size on one GPU (docs/VALIDATION.md, "Silo
# discharge"): five orifices D0 = 5-15 d in a silo 40 d wide filled 50 d high
# (~75k spheres each), discharged for 1 s of steady flow; the Beverloo fit,
# the table and a plot.
#   bench/validation_silo_gpu.sh BUILD_DIR OUT [--backend cuda]
# Writes OUT/silo_full.md (table and fit), OUT/silo_full.png (flow curves and
# W against D0 with the Beverloo band) and the runs' log lines; the runs
# themselves (CSV snapshots, ~50 MB) stay in RUNS (default /tmp/silo_full_runs).
set -uo pipefail
build=$(cd "$1" && pwd)
out=$2
shift 2
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
{
  date -u
  nvidia-smi --query-gpu=name --format=csv,noheader 2>/dev/null || true
  git -C "$root" rev-parse --short HEAD 2>/dev/null || true
} > "$out/silo_full.md"
python3 "$root/tools/silo_beverloo.py" "$build/src/grainstorm" --variant full --backend cuda \
  --keep "${RUNS:=/tmp/silo_full_runs}" --plot "$out/silo_full.png" "$@" 2>&1 | tee -a "$out/silo_full.md"
status=${PIPESTATUS[0]}
# The runs' logs (what each step cost) beside the table.
for d in "$RUNS"/silo_D0_*/; do
  [[ -f $d/run.log ]] && grep -E "^(done|time per phase|particles at the end)" "$d/run.log" | sed "s|^|$(basename "$d"): |"
done >> "$out/silo_full.md"
exit "$status"
