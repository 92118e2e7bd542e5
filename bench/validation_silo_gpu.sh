#!/usr/bin/env bash
# The silo validation at full size on one GPU, within a wall budget
# (docs/VALIDATION.md, "Silo discharge"; tools/silo_beverloo.py --variant full):
# five orifices D0 = 6, 8, 10, 12.5, 15 d in a flat-bottomed silo 46 d wide
# filled 58 d high, so that every orifice meets Mankoc et al.'s (2007)
# conditions (silo diameter above 2.5 D0 and above D0 + 30 d; fill above 1.2
# silo diameters), the five runs side by side on the one GPU. Each starts
# from a random fill of 105,716 spheres (2 mm, radii +-10 %) that settles
# behind the closed gate until 0.45 s; the inlet keeps the level from 0.3 s
# on; the flow through the orifice is measured over 0.6-1.2 s (steady flow:
# the two halves are compared); the Beverloo fit of C and k, the table and a
# plot.
#
#   [BUDGET_S=480] [BACKEND=cuda] [SIZE=full] [MPS=0] [JOBS=5] bench/validation_silo_gpu.sh BUILD_DIR OUT
#
# SIZE=smoke with BACKEND=cpu checks this script on a CPU in about a minute.
# The runs get BUDGET_S less the time so far and 60 s for the analysis;
# then any still going is stopped (SIGTERM: grainstorm stops and flushes its
# logs) and analysed over the window it reached (at least 0.15 s), marked
# "stopped by the budget" in the table. A missing BUILD_DIR/src/grainstorm
# is built first (on the budget's time). MPS=1 starts a private CUDA MPS
# daemon for the runs (and quits it at the end), so that their kernels can
# run at once rather than in time slices.
#
# Estimate (not measured: no GPU where this was written). Per run 71,532
# steps (dt = 16.8 us, 0.1 of the contact time at 1000 N/m, to t = 1.2 s) of
# about 106k spheres: 7.6e9 particle-steps, 3.8e10 for the five. On one H200
# a scene of 7.7k-77k spheres takes 0.27-0.5 ms per step alone
# (docs/PERFORMANCE.md: mixer case a 0.27 ms, case b 76.8k 0.49 ms); at
# 106k say 0.4-0.6 ms, so one run alone ~30-45 s; five side by side share
# the GPU: at worst they take the sum of their steps (150-215 s), at best
# (each run leaves the GPU idle between its launches) about 60-100 s. On
# the CPU (6.4e5 particle-steps/s per core under load, docs/VALIDATION.md)
# the five would take about 16 core-hours.
#
# Writes OUT/silo_results.md (machine, commit, plan, table and fit: paste into
# docs/VALIDATION.md), OUT/silo_results.png (mass through the orifice against
# time, W against D0 with the Beverloo band and the fit), OUT/silo_progress.log
# (the timestamped progress lines, also on stderr), OUT/env.txt and OUT/runs
# (each run's logs without its snapshots, to analyse and plot again
# elsewhere: tools/silo_beverloo.py --variant full --analyse OUT/runs --plot
# FILE; the overlaps need the snapshots); the runs themselves (CSV snapshots,
# ~60 MB) stay in RUNS (default /tmp/silo_full_runs).
set -uo pipefail
[[ $# -ge 2 ]] || { echo "usage: $0 BUILD_DIR OUT" >&2; exit 2; }
source "$(dirname "$0")/validation_common.sh"
validation_setup silo "$1" "$2"
variant=$size
runs=${RUNS:-/tmp/silo_${variant}_runs}
rm -rf "$runs"
jobs=${JOBS:-5}
results=$out/silo_results.md
cp "$out/env.txt" "$results"
echo >> "$results"
run_tool "$python" "$root/tools/silo_beverloo.py" "$binary" --variant "$variant" --backend "$backend" \
  --jobs "$jobs" --budget-s "$(runs_budget 60)" --keep "$runs" --plot "$out/silo_results.png" \
  > "$out/silo_table.txt" 2> >(tee "$out/silo_progress.log" >&2)
status=$?
sleep 1   # the progress log's tee (a process substitution) writes its last lines
# The runs' logs without their snapshots (kilobytes): the table and the plot
# can be made again from them anywhere (overlaps excepted):
#   tools/silo_beverloo.py --variant full --analyse OUT/runs --plot silo_results.png
for d in "$runs"/silo_D0_*/; do
  [[ -d $d ]] || continue
  mkdir -p "$out/runs/$(basename "$d")"
  cp "$d"/*.csv "$d"/run.log "$out/runs/$(basename "$d")/" 2>/dev/null
  rm -f "$out/runs/$(basename "$d")"/particles_*.csv
done
cat "$out/silo_table.txt" >> "$results"
[[ -f $out/silo_results.png ]] || echo "no plot (no matplotlib here): make it from the logs in OUT/runs with
  tools/silo_beverloo.py --variant $variant --analyse OUT/runs --plot OUT/silo_results.png" >> "$results"
{
  echo
  echo "Each run's log (particle-steps/s over its run, the time per phase):"
  echo
  for d in "$runs"/silo_D0_*/; do
    [[ -f $d/run.log ]] && grep -E "^(done|stopped by a signal|time per phase|particles at the end)" "$d/run.log" |
      sed "s|^|    $(basename "$d"): |"
  done
  echo
  echo "tools/silo_beverloo.py exit status $status after $(( $(date +%s) - t_start )) s of the ${budget} s budget"
} >> "$results"
validation_finish "$results" "$status"
