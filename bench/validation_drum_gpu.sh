#!/usr/bin/env bash
# The rotating drum at full size on one GPU, within a wall budget
# (docs/VALIDATION.md, "Rotating drum"; tools/drum.py --variant full): a drum
# of radius 50 d, periodic along its axis over 20 d, 30 % full of 13,500
# glass spheres (2 mm), at 13 cases side by side on the one GPU: Fr =
# 3e-3 ... 3 (regime against rotation rate: rolling, cascading, cataracting,
# centrifuging) without rolling resistance, and rolling_friction 0.1, 0.2, 0.4
# at Fr 0.01 and 0.3 at Fr 0.1 (dynamic angle against rolling resistance).
# Each settles for 0.4 s, turns 1.5 rad to reach its angle and 1.5 rad
# measured (a bed at Fr >= 0.3: 2 revolutions to spin up, one measured).
#
#   [BUDGET_S=480] [BACKEND=cuda] [SIZE=full] [MPS=0] bench/validation_drum_gpu.sh BUILD_DIR OUT
#
# SIZE=ci with BACKEND=cpu checks this script on a CPU in a few minutes.
# The runs get BUDGET_S less the time so far and 45 s for the analysis;
# then any still going is stopped (SIGTERM: grainstorm stops at the next
# step) and measured over the snapshots of its window written so far (at
# least 3), the table saying how many of the planned ones. A missing
# BUILD_DIR/src/grainstorm is built first (on the budget's time).
# MPS=1 starts a private CUDA MPS daemon for the runs (quit at the end), so
# that their kernels can run at once rather than in time slices.
#
# Estimate (made before any GPU run). dt = 27.8 us (0.1 of the contact
# time at 500 N/m); the cases take 39k (Fr 0.1) to 155k (Fr 3e-3) steps
# (as measured: 38,771 and 155,124), 1.0e6 steps and 1.35e10 particle-steps
# in all. On one H200 a scene of this size is launch-bound: ~0.27 ms per
# step alone (docs/PERFORMANCE.md: 7,680 spheres, 0.27 ms), so the longest case alone
# ~42 s and all 13 one after the other ~270 s; side by side the GPU runs
# other cases' kernels while one waits on its host, so the wall time should
# lie between the longest case (~45 s) and the serial sum (~270 s). The
# Fr = 1e-3 case of the earlier plan (2.6e5 steps) is left out for that
# reason. Measured (2026-12-03, one H200, beside the silo and chute scripts
# under one MPS daemon; docs/data/validation_full/drum_results.md): each run
# 64-129 s, tools/drum.py done 139 s into the 382 s budget.
#
# Writes OUT/drum_results.md (machine, commit, plan, the table: paste into
# docs/VALIDATION.md), OUT/drum_angle_<backend>.png (angle against Fr and
# against rolling friction), OUT/drum_sections_<backend>.png (each case's last
# cross-section), OUT/drum_results.json (the numbers and the last
# cross-sections: tools/drum.py --replot FILE --plots DIR makes the plots
# where matplotlib is), OUT/drum_progress.log (the timestamped progress lines, also
# on stderr), OUT/env.txt, and OUT/runs/<backend>/*.yaml, run.log and
# timeseries.csv of every case (the snapshots are deleted once measured).
set -uo pipefail
[[ $# -ge 2 ]] || { echo "usage: $0 BUILD_DIR OUT" >&2; exit 2; }
source "$(dirname "$0")/validation_common.sh"
validation_setup drum "$1" "$2"
rm -rf "$out/runs"
results=$out/drum_results.md
cp "$out/env.txt" "$results"
echo >> "$results"
run_tool "$python" "$root/tools/drum.py" "$binary" --variant "$size" --backends "$backend" \
  --jobs "${JOBS:-16}" --budget-s "$(runs_budget 45)" --keep "$out/runs" --prune --plots "$out" --save "$out/drum_results.json" \
  > "$out/drum_table.txt" 2> >(tee "$out/drum_progress.log" >&2)
status=$?
sleep 1   # the progress log's tee (a process substitution) writes its last lines
cat "$out/drum_table.txt" >> "$results"
[[ -f $out/drum_angle_$backend.png ]] || echo "no plots (no matplotlib here): make them from the saved results with
  tools/drum.py --replot OUT/drum_results.json --plots OUT" >> "$results"
echo "tools/drum.py exit status $status after $(( $(date +%s) - t_start )) s of the ${budget} s budget" >> "$results"
validation_finish "$results" "$status"
