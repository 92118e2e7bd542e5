#!/usr/bin/env bash
# A run into an output directory that already holds files (CTest, CPU ranks):
#  1. is refused, on 1 and on 2 ranks, with a message naming the directory and
#     --overwrite, and changes nothing in it;
#  2. with --overwrite, writes what a run into a new directory writes: the
#     earlier run's files are gone (an old snapshot the new run would not
#     write, the log and the time series), other files are kept;
#  3. with --restart into it (a run continued from one of its checkpoints),
#     leaves exactly the files and rows of the uninterrupted run: no time-series
#     row twice;
#  4. --overwrite with --restart is refused.
# usage: output_directory.sh GRAINSTORM MPIEXEC SCENE WORKDIR
set -euo pipefail
gs=$1 mpiexec=$2 scene=$3 work=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work"
export OMP_NUM_THREADS=1 OMP_WAIT_POLICY=passive
fail() { echo "FAIL: $*" >&2; exit 1; }
fingerprint() { (cd "$1" && find . -type f | sort | xargs md5sum); }
steps=$(( $("$gs" check "$scene" | awk '/^steps:/ {print $2}') ))
run_steps=$(( steps / 4 ))  # past two checkpoints (every 0.05 s)

# 1. Refused, nothing changed.
"$gs" run "$scene" --backend cpu --steps $run_steps --out d > first.log
before=$(fingerprint d)
for launcher in "" "timeout 60 $mpiexec --oversubscribe --allow-run-as-root -np 2"; do
  set +e; $launcher "$gs" run "$scene" --backend cpu --steps $run_steps --out d > again.out 2> again.err; code=$?; set -e
  [[ $code != 0 && $code != 124 ]] || fail "a run into a non-empty directory: exit code $code (${launcher:-one rank})"
  [[ $(grep -c "^grainstorm: error" again.err) == 1 ]] || fail "not one message: $(cat again.err)"
  grep -q "output directory d is not empty.*--overwrite" again.err || fail "the refusal: $(cat again.err)"
  [[ $(fingerprint d) == "$before" ]] || fail "the refused run changed d (${launcher:-one rank})"
done
echo "non-empty directory refused: $(cat again.err)"

# 2. --overwrite: as a run into a new directory, other files kept.
touch d/particles_9999999990.csv d/notes.txt
half=$(( run_steps / 2 ))
"$gs" run "$scene" --backend cpu --steps $half --out new > /dev/null
"$gs" run "$scene" --backend cpu --steps $half --out d --overwrite > /dev/null
[[ -e d/notes.txt ]] || fail "--overwrite removed a file grainstorm does not write"
rm d/notes.txt
[[ $(cd d && ls) == $(cd new && ls) ]] || fail "--overwrite left other files: $(cd d && ls)"
cmp d/timeseries.csv new/timeseries.csv || fail "--overwrite: the time series differs from a new run's"
[[ $(grep -c "^grainstorm " d/run.log) == 1 ]] || fail "--overwrite: run.log holds the earlier run"
echo "--overwrite: the same files as a run into a new directory"

# 3. --restart into the directory: the files of the uninterrupted run.
"$gs" run "$scene" --backend cpu --steps $run_steps --out full > /dev/null
cp -r full continued
checkpoint=$(ls continued/checkpoint_*.h5 | sort | head -1)
"$mpiexec" --oversubscribe --allow-run-as-root -np 2 "$gs" run "$scene" --backend cpu --restart "$checkpoint" \
  --steps $run_steps --out continued > /dev/null
cmp full/timeseries.csv continued/timeseries.csv || fail "--restart into the directory: the time series differs"
[[ $(cd full && ls) == $(cd continued && ls) ]] || fail "--restart: other files: $(cd continued && ls)"
for f in full/particles_*.csv; do cmp "$f" "continued/$(basename "$f")" || fail "--restart: $f differs"; done
echo "--restart into the directory: the uninterrupted run's files and rows"

# 4. Both.
set +e; "$gs" run "$scene" --backend cpu --restart "$checkpoint" --overwrite --out continued 2> both.err; code=$?; set -e
[[ $code != 0 ]] && grep -q "exclude each other" both.err || fail "--overwrite --restart: $code $(cat both.err)"
