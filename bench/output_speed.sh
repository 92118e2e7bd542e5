#!/usr/bin/env bash
# Output speed of a run: snapshots and a checkpoint of a lattice bed
# (bench/lattice_bed.sh) on one rank, 2 steps: the initial and the final
# snapshot, and a checkpoint at the end. 24e6 frictional spheres (every
# snapshot field, a checkpoint with contact history), and 1e8 without
# friction and with the default fields (no history: the files, about 30 GB
# in all, fit the machine's disk and the checkpoint its host memory).
#   bench/output_speed.sh BUILD OUT [BEFORE_BUILD] [BACKEND=cuda] [COUNTS="24000000 100000000"]
# Files go to $OUTPUT_SPEED_DIR (default /tmp/output_speed) and are removed
# after each run; OUT gets each run's log and output_speed.txt, one line per
# run: the bytes written, the run's output time (its phase line: wall time
# outside the steps, the host copies included) and GB/s over it, and for
# builds that log them, each file's own write speed (the time on the
# writer's thread).
set -euo pipefail
build=$1 out=$2 before=${3:-} backend=${4:-cuda} counts=${5:-"24000000 100000000"}
work=${OUTPUT_SPEED_DIR:-/tmp/output_speed}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out" "$work"
py() { python3 -c "print($1)"; }
result=$out/output_speed.txt
: > "$result"

run_case() {  # label build count friction fields
  local label=$1 bin=$2/src/grainstorm count=$3 friction=$4 fields=$5
  local side layers scene=$work/bed.yaml dir=$work/run log=$out/${label}_$count.log
  side=$(py "round(($count / 2) ** (1/3))")
  layers=$(py "round($count / $side**2)")
  "$here/lattice_bed.sh" "$side" "$layers" "$dir" "$fields" |
    sed "s/^output: {interval: 0, /output: {interval: 0, checkpoint_interval: 1, /; s/friction: true/friction: $friction/" \
    > "$scene"
  rm -rf "$dir"
  local code=0
  timeout 150 "$bin" run "$scene" --backend "$backend" --steps 2 --overwrite > "$log" 2>&1 || code=$?
  local bytes output
  bytes=$(du -cb "$dir"/particles_*.h5 "$dir"/checkpoint_*.h5 2>/dev/null | tail -1 | cut -f1)
  output=$(sed -n 's/.*output \([0-9.]*\), total wall.*/\1/p' "$log")
  local line="$label n=$count friction=$friction exit=$code bytes=${bytes:-0} output_s=${output:-none}"
  [[ -n $output ]] && line+=" gbps=$(py "round(${bytes:-0} / 1e9 / max($output, 1e-9), 3)")"
  local files
  files=$(grep -E "^(snapshot|checkpoint): .*GB/s" "$log" | sed -E 's|: [^ ]*/([^/ ]*\.h5)|: \1|' | tr '\n' ';' || true)
  [[ -n $files ]] && line+=" files: $files"
  echo "$line" | tee -a "$result"
  rm -rf "$dir"
}

for count in $counts; do
  friction=true
  fields="id, material, marker, radius, mass, inertia, position, velocity, angular_velocity, orientation, force, torque"
  if [[ $count -gt 50000000 ]]; then friction=false fields=""; fi
  run_case after "$build" "$count" "$friction" "$fields"
  [[ -n $before ]] && run_case before "$before" "$count" "$friction" "$fields"
done
nvidia-smi --query-gpu=name --format=csv,noheader >> "$result" 2>/dev/null || true
echo "commit $(git -C "$here" rev-parse --short HEAD 2>/dev/null || echo unknown), $(date -u +%F)" >> "$result"
