#!/usr/bin/env bash
# Removal through the command line (CTest, CPU-emulated ranks), on a small
# wedge hopper discharging into an outlet (tests/cli/discharge.yaml):
#  1. removed.csv accounts for every particle created: counts and masses per
#     material and marker, and the particle counts of timeseries.csv;
#  2. 2 and 3 ranks write the same snapshots, timeseries.csv and removed.csv
#     as 1 rank, byte for byte;
#  3. a run continued from a checkpoint in the middle of the discharge, in its
#     own directory after the first run went on past it (as after a kill),
#     writes the same files as the uninterrupted run;
#  4. --overwrite starts removed.csv afresh.
# usage: discharge.sh GRAINSTORM MPIEXEC SCENE WORKDIR
set -euo pipefail
gs=$1 mpiexec=$2 scene=$3 work=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work"
export OMP_NUM_THREADS=1 OMP_WAIT_POLICY=passive
mpi() { local np=$1; shift; "$mpiexec" --oversubscribe --allow-run-as-root -np "$np" "$gs" "$@"; }
fail() { echo "FAIL: $*" >&2; exit 1; }
# Every file the runs in $1 and $2 wrote but the log and the checkpoints, equal.
same_files() {
  for f in "$1"/particles_*.csv "$1"/timeseries.csv "$1"/removed.csv; do
    cmp "$f" "$2/$(basename "$f")" || fail "$2/$(basename "$f") differs from $f"
  done
  [[ $(ls "$1"/particles_*.csv | wc -l) == $(ls "$2"/particles_*.csv | wc -l) ]] || fail "$2: other snapshots than $1"
}

"$gs" run "$scene" --backend cpu --out one > one.log
[[ $(head -1 one/removed.csv) == "time,step,outlet,material,marker,count,mass,outlet_count,outlet_mass" ]] ||
  fail "removed.csv header: $(head -1 one/removed.csv)"

# 1. The scene creates 60 glass spheres (marker 1) and 60 steel ones (marker
#    0), all of radius 0.5 mm; the run lasts until every one has left.
awk -F, -v glass=$(( 2500 )) -v steel=$(( 7800 )) '
  NR == 1 { next }
  { n[$4 "," $5] += $6; m[$4 "," $5] += $7; total = $8; if ($2 < last) bad = "steps out of order"; last = $2 }
  END {
    v = 4 / 3 * 3.14159265358979 * 0.0005 ^ 3
    if (bad != "") { print bad; exit 1 }
    if (n["glass,1"] != 60 || n["steel,0"] != 60 || length(n) != 2) { print "counts", n["glass,1"], n["steel,0"]; exit 1 }
    if (total != 120) { print "outlet_count ends at " total; exit 1 }
    for (k in m) { want = (k == "glass,1" ? glass : steel) * v * 60; if ((m[k] - want) ^ 2 > (1e-6 * want) ^ 2) { print k, m[k], want; exit 1 } }
  }' one/removed.csv || fail "removed.csv does not account for the particles created"
# Particles in timeseries.csv plus those removed up to its step: always 120.
awk -F, 'NR == FNR { if (FNR > 1) { step[FNR] = $2; count[FNR] = $6 } rows = FNR; next }
  FNR > 1 { gone = 0; for (r = 2; r <= rows; ++r) if (step[r] <= $1) gone += count[r]
            if ($3 + gone != 120) { print "step " $1 ": " $3 " particles and " gone " removed"; exit 1 } }' \
  one/removed.csv one/timeseries.csv || fail "particle counts in timeseries.csv"
grep -q "particles at the end: 0" one/run.log || fail "the log does not give the final count"
echo "removed.csv accounts for every particle: $(( $(wc -l < one/removed.csv) - 1 )) rows"

# 2. Ranks.
for np in 2 3; do
  mpi $np run "$scene" --backend cpu --out "ranks$np" > "ranks$np.log"
  same_files one "ranks$np"
done
echo "2 and 3 ranks: the same files as 1"

# 3. Restart in the middle of the discharge (the checkpoint at 0.04 s), after
#    the first run went on to 0.06 s and wrote rows past the checkpoint.
steps=$(( $("$gs" check "$scene" | awk '/^steps:/ {print $2}') ))
mpi 2 run "$scene" --backend cpu --steps $(( steps * 3 / 4 )) --out cont > cont.log
checkpoint=$(ls cont/checkpoint_*.h5 | sort | head -1)
grep -q "checkpoint_0000002575" <<< "$checkpoint" || fail "expected the checkpoint at step 2575, got $checkpoint"
mid=$(awk -F, 'NR > 1 && $2 <= 2575 { n = $8 } END { print n }' cont/removed.csv)
late=$(awk -F, 'NR > 1 && $2 > 2575 { n++ } END { print n + 0 }' cont/removed.csv)
(( mid > 0 && late > 0 )) || fail "the checkpoint is not in the middle of the discharge ($mid before, $late rows after)"
mpi 3 run "$scene" --backend cpu --restart "$checkpoint" --out cont > cont2.log
same_files one cont
echo "restart mid-discharge ($mid removed before it) on other ranks: the same files"

# 4. --overwrite.
echo "0.5,1,orifice,glass,1,1,1,1,1" >> one/removed.csv
"$gs" run "$scene" --backend cpu --out one --overwrite > /dev/null
same_files ranks2 one
echo "--overwrite: removed.csv afresh"
