#!/usr/bin/env bash
# Inclined chute flow on a rough base at full size on one GPU, within a wall
# budget (docs/VALIDATION.md, "Inclined chute flow"; Silbert et al., Phys.
# Rev. E 64, 051302, 2001; tools/chute_flow.py --preset full): a box of
# 20 d x 10 d (Silbert's as remembered, not confirmed), periodic in the
# flow (x) and cross (y) directions, H = 20 (4,000 flowing spheres on 240
# frozen ones of a rough base), at ten angles
# 17, 18, ... 26 deg side by side on the one GPU, each for 200 tau from a
# pour in simple shear, the profile averaged over the second 100 tau; the
# flow/no-flow angle lies between the highest angle that stops and the lowest
# that flows (1 deg apart: no bisection, whose runs would follow each
# other). Contacts 10x softer than Silbert's (k_n = 2e4 m g / d: overlaps
# ~H/k_n = 1e-3 d at the base), steps of t_c / 10.
#
#   [BUDGET_S=480] [BACKEND=cuda] [SIZE=full] [MPS=0] bench/validation_chute_gpu.sh BUILD_DIR OUT
#
# SIZE=smoke with BACKEND=cpu checks this script on a CPU in a few minutes
# (the ci layer, two angles, 20 tau). The runs get BUDGET_S less the time
# so far and 30 s for the analysis; then any still going is stopped
# (SIGTERM: grainstorm stops and flushes its measurement logs) and analysed
# over the time it reached (the table's "t reached"; its profile from the
# samples after 100 tau, none before). A missing BUILD_DIR/src/grainstorm is
# built first (on the budget's time).
# MPS=1 starts a private CUDA MPS daemon for the runs (quit at the end), so
# that their kernels can run at once rather than in time slices.
#
# Estimate (not measured: no GPU where this was written). dt = 21.9 us
# (t_c / 10; tau = 14.3 ms), 130,689 steps per run of 4,240 particles:
# 5.5e8 particle-steps per run, 5.5e9 for the ten, 1.3e6 steps. On one H200
# a scene this small is launch-bound: ~0.2-0.27 ms per step alone
# (docs/PERFORMANCE.md: 7,680 spheres, 0.27 ms), so one run alone ~30-35 s
# and the ten one after the other ~260-350 s; side by side the GPU runs other
# runs' kernels while one waits on its host, so the wall time should lie
# between ~35 s and that sum. Silbert's own stiffness (2e5) and t_c / 20
# would cost 6.3x more steps: not within one budget.
#
# Writes OUT/chute_results.md (machine, commit, plan, the table: paste into
# docs/VALIDATION.md), OUT/chute_summary.md, chute_profiles.csv,
# chute_energy.csv, the plots chute_profiles.png (velocity with the Bagnold
# fits, solid fraction, bulk solid fraction against theta) and
# chute_energy.png, OUT/chute_progress.log (the timestamped progress lines,
# also on stderr), OUT/env.txt, and the runs' scenes and logs in OUT/runs
# (no snapshots): tools/chute_flow.py - --preset full --reuse --work OUT/runs
# --out DIR analyses and plots them again where matplotlib is.
set -uo pipefail
[[ $# -ge 2 ]] || { echo "usage: $0 BUILD_DIR OUT" >&2; exit 2; }
source "$(dirname "$0")/validation_common.sh"
validation_setup chute "$1" "$2"
extra=()
preset=$size
if [[ $size == smoke ]]; then
  preset=ci
  extra=(--angles 24,14 --duration 20)
fi
rm -rf "$out/runs"
results=$out/chute_results.md
cp "$out/env.txt" "$results"
echo >> "$results"
run_tool "$python" "$root/tools/chute_flow.py" "$binary" --preset "$preset" "${extra[@]}" --backend "$backend" \
  --jobs "${JOBS:-16}" --budget-s "$(runs_budget 30)" --out "$out" --work "$out/runs" \
  > "$out/chute_table.txt" 2> >(tee "$out/chute_progress.log" >&2)
status=$?
sleep 1   # the progress log's tee (a process substitution) writes its last lines
rm -f "$out"/runs/*/out/particles_*.csv   # not needed to analyse again (the layer logs are)
{
  # The summary (written when the runs were analysed), else what the tool printed.
  if [[ -f $out/chute_summary.md ]]; then cat "$out/chute_summary.md"; else cat "$out/chute_table.txt"; fi
  [[ -f $out/chute_profiles.png ]] || echo "no plots (no matplotlib here): make them from the runs' logs with
  tools/chute_flow.py - --preset $preset ${extra[*]} --reuse --work OUT/runs --out OUT"
  echo
  echo "tools/chute_flow.py exit status $status after $(( $(date +%s) - t_start )) s of the ${budget} s budget"
} >> "$results"
validation_finish "$results" "$status"
