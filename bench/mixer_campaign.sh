#!/usr/bin/env bash
# Advances a campaign of mixer runs by one job on a GPU machine: each unfinished run
# continues from its newest checkpoint, the lot stops before BUDGET_S seconds
# of wall time (counted from this script's start, a build included), and what
# the next job needs comes back under OUT. docs/MIXER.md, "Running the
# study across sessions", has the whole procedure.
#
#   [BUDGET_S=480] [JOBS=1] [MPS=0] [BACKEND=cuda] [RESERVE_S=40] [MIN_PIECE_S=60] [PACK=1] [RETRY=0]
#   [KEEP_REVOLUTIONS="REV ..." (default none kept; e.g. "0 1 5 10 32")] [KEEP_RUNS='*_s1']
#     bench/mixer_campaign.sh BUILD CAMPAIGN_DIR OUT
#
# CAMPAIGN_DIR holds the runs' scenes (NAME.yaml, written by
# tools/make_mixer_cases.py --out-dir CAMPAIGN_DIR), impeller.stl, and per run
# that has started a directory NAME/ with its newest checkpoint, mixing.csv,
# timeseries.csv, run.log and campaign.log (one line per piece). It is read,
# never written: the runs go on in a copy under WORK (default a new temporary
# directory). Runs are taken in name order, JOBS at a time; with MPS=1 (CUDA)
# a CUDA MPS daemon of the job's own lets the JOBS processes run their kernels
# at once (bench/mps.sh), without it they take turns on the GPU. A run's piece is
# stopped by SIGTERM at the budget, on which grainstorm writes a checkpoint
# of the step it stops at and exits with code 3.
#
# OUT receives the campaign in the same layout (scenes, impeller.stl, per run
# the newest checkpoint unless it has finished, the logs, the fault snapshot
# of a run whose last piece failed if at most 16 MiB; no snapshots except,
# for the runs whose names match the glob KEEP_RUNS, those nearest the
# revolutions of KEEP_REVOLUTIONS, for top views), packed as
# campaign.tar.gz.partNN of at most 15 MiB (a job system may return at most 8
# files of 16 MiB), and progress.txt. Put it back into the campaign directory
# (each run directory in it replaces the one there whole):
#   tools/mixer_campaign.py restore OUT CAMPAIGN_DIR
# PACK=0 writes the layout itself under OUT instead (for a local machine).
# A run whose last piece failed (exit code other than 0 or 3: a fault, a
# refused restart) is skipped until RETRY=1.
set -uo pipefail
start=$(date +%s)
(($# == 3)) || { echo "usage: [BUDGET_S=480] [JOBS=1] [BACKEND=cuda] ... bench/mixer_campaign.sh BUILD CAMPAIGN_DIR OUT"; exit 2; }
build=$1 campaign=$2 out=$3
budget=${BUDGET_S:-480} jobs=${JOBS:-1} backend=${BACKEND:-cuda} reserve=${RESERVE_S:-40}
root=$(pwd)
elapsed() { echo $(($(date +%s) - start)); }

[[ -d $campaign && -f $campaign/impeller.stl ]] ||
  { echo "mixer_campaign: $campaign is not a campaign directory (it needs impeller.stl and NAME.yaml scenes)"; exit 1; }
scenes=$(cd "$campaign" && ls *.yaml 2>/dev/null | sort)
[[ -n $scenes ]] || { echo "mixer_campaign: no scenes (*.yaml) in $campaign"; exit 1; }
mkdir -p "$out"

# The build, when the binary is not there yet (a fresh device machine).
source "$root/bench/carried_deps.sh"
use_carried_deps "$root"
gs=$build/src/grainstorm
if [[ ! -x $gs ]]; then
  cuda=OFF; [[ $backend == cuda ]] && cuda=ON
  { cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DGS_ENABLE_CUDA=$cuda "${extra[@]}" &&
    cmake --build "$build" -j "$(nproc)" --target grainstorm; } > "$out/build.log" 2>&1 ||
    { tail -40 "$out/build.log"; exit 1; }
  echo "build: $(elapsed) s"
fi
gs=$(realpath "$gs")

work=${WORK:-$(mktemp -d /tmp/mixer_campaign.XXXXXX)}
mkdir -p "$work"
cp -a "$campaign"/. "$work"/
work=$(realpath "$work")
if [[ ${MPS:-0} == 1 && $backend == cuda ]]; then
  source "$root/bench/mps.sh"
  start_mps "$work.mps" && echo "MPS daemon started" || echo "MPS daemon did not start: the runs take turns on the GPU"
fi

newest_checkpoint() {  # the newest checkpoint of run dir $1 that reads whole
  local f
  for f in $(ls "$1"/checkpoint_*.h5 2>/dev/null | sort -r); do
    "$gs" info "$f" > /dev/null 2>&1 && { echo "$f"; return; }
  done
}

# One piece of run $1 until the deadline $2 (epoch seconds).
piece() {
  local name=$1 deadline=$2 dir=$work/$1 last args rc t0 limit
  mkdir -p "$dir"
  last=$(newest_checkpoint "$dir")
  args=(run "$name.yaml" --backend "$backend" --out "$name")
  if [[ -n $last ]]; then args+=(--restart "$name/$(basename "$last")"); else args+=(--overwrite); fi
  t0=$(date +%s) limit=$((deadline - t0))
  # SIGTERM at the deadline; a run that has not stopped 30 s later is killed
  # (its last periodic checkpoint is then the one to go on from).
  (cd "$work" && timeout --preserve-status -k 30 -s TERM "$limit" "$gs" "${args[@]}" > "$dir/piece.out" 2>&1)
  rc=$?
  printf '%s from %s wall_s %d exit %d\n' "$(date -u +%FT%TZ)" "$(basename "${last:-start}")" \
    $(($(date +%s) - t0)) "$rc" >> "$dir/campaign.log"
  echo "$name: $( ((rc == 0)) && echo finished || { ((rc == 3)) && echo "stopped, to be continued" || echo "FAILED (exit $rc): $dir/piece.out"; })"
}

deadline=$((start + budget - reserve))
running=0
for scene in $scenes; do
  name=${scene%.yaml} log=$work/$name/campaign.log
  [[ -f $log ]] && grep -q ' exit 0$' "$log" && continue
  if [[ -f $log && ${RETRY:-0} != 1 ]] && tail -1 "$log" | grep -qv -E ' exit (0|3)$'; then
    echo "$name: skipped, its last piece failed ($(tail -1 "$log")); RETRY=1 tries again"; continue
  fi
  while ((running >= jobs)); do wait -n; running=$((running - 1)); done
  # A piece shorter than MIN_PIECE_S would spend much of it starting up.
  if (($(date +%s) + ${MIN_PIECE_S:-60} > deadline)); then
    echo "$name and later runs: left for the next job (less than ${MIN_PIECE_S:-60} s left)"; break
  fi
  piece "$name" "$deadline" &
  running=$((running + 1))
done
wait

# What the next job needs: scenes, the mesh, per run the newest
# checkpoint, the logs and the snapshots KEEP_REVOLUTIONS asks for; older
# checkpoints and other snapshots stay behind.
pack=$work.pack
rm -rf "$pack" && mkdir -p "$pack"
cp -a "$work"/*.yaml "$work"/impeller.stl "$pack"/
for scene in $scenes; do
  name=${scene%.yaml}
  [[ -d $work/$name ]] || continue
  mkdir -p "$pack/$name"
  for f in mixing.csv timeseries.csv run.log campaign.log piece.out; do
    [[ -f $work/$name/$f ]] && cp -a "$work/$name/$f" "$pack/$name/"
  done
  # Snapshots for the top views (tools/mixer_campaign.py snapshots), kept from job to job.
  if [[ -n ${KEEP_REVOLUTIONS:-} && $name == ${KEEP_RUNS:-*_s1} ]]; then
    python3 tools/mixer_campaign.py snapshots "$work/$name" "$work/$scene" $KEEP_REVOLUTIONS 2>/dev/null |
      while read -r f; do cp -a "$f" "$pack/$name/"; done
  fi
  # A run whose last piece failed: the state it stopped in (grainstorm's
  # fault snapshot, the newest), to see why, where it is small enough to
  # carry (16 MiB: mixer case a's is 0.5 MB, case c's far more).
  if tail -1 "$work/$name/campaign.log" 2>/dev/null | grep -q -v -E ' exit (0|3)$'; then
    fault=$(ls "$work/$name"/fault_*.h5 2>/dev/null | sort | tail -1)
    [[ -n $fault ]] && (($(stat -c %s "$fault") <= 16 * 1048576)) && cp -a "$fault" "$pack/$name/"
  fi
  # A finished run needs no checkpoint to go on from.
  tail -1 "$work/$name/campaign.log" 2>/dev/null | grep -q ' exit 0$' && continue
  last=$(newest_checkpoint "$work/$name")
  [[ -n $last ]] && cp -a "$last" "$pack/$name/"
done
python3 tools/mixer_campaign.py progress "$pack" | tee "$out/progress.txt"
if [[ ${PACK:-1} == 1 ]]; then
  tar czf - -C "$pack" . | split -b 15M -d - "$out/campaign.tar.gz.part"
  size=$(cat "$out"/campaign.tar.gz.part* | wc -c)
  echo "packed: $(ls "$out"/campaign.tar.gz.part* | wc -l) part(s), $((size / 1048576)) MiB"
  ((size > 60 * 1048576)) && echo "WARNING: more than 60 MiB: more than a short job may return (64 MiB); split the campaign"
else
  cp -a "$pack"/. "$out"/
fi
echo "total: $(elapsed) s of a budget of $budget s"
