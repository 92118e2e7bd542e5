#!/usr/bin/env bash
# Runs a mixer case for at most LIMIT seconds of wall time (then SIGTERM: the
# run checkpoints and stops, its mixing.csv holds what was reached), renders
# top views of the marking and the last snapshot, and plots the mixing curve.
#   bench/mixer_run.sh BUILD_DIR CASE LIMIT_S OUTDIR [BACKEND]
set -uo pipefail
build=$1 case=$2 limit=$3 out=$4 backend=${5:-cuda}
root=$(pwd)
mkdir -p "$out"
run=$out/mixer_$case
(cd cases/mixer && timeout -s TERM "$limit" "$root/$build/src/grainstorm" run "case_$case.yaml" --backend "$backend" \
   --out "$run" --overwrite > "$out/mixer_$case.log" 2>&1)
echo "case $case: exit $? after at most $limit s"
grep -E "particles,|marked|done|stopped|time per phase|peak" "$out/mixer_$case.log"
tail -2 "$out/mixer_$case.log" | tr '\r' '\n' | tail -1
cat "$run/mixing.csv"
snaps=($(ls "$run"/particles_*.h5 2>/dev/null | sort))
# Snapshots land every settling time: the second one is at the marking.
((${#snaps[@]} > 1)) && python3 tools/render_topview.py "${snaps[1]}" -o "$out/case_${case}_marked.png" --size 800
((${#snaps[@]} > 2)) && python3 tools/render_topview.py "${snaps[-1]}" -o "$out/case_${case}_last.png" --size 800
python3 tools/plot_mixing.py --run "case $case=$run/mixing.csv" --out-dir "$out" --prefix "case_${case}"
rm -f "$run"/particles_*.h5 "$run"/checkpoint_*.h5
