#!/usr/bin/env bash
# The measurements' logs and grids (docs/MEASUREMENTS.md) through the command
# line (CTest, CPU-emulated ranks):
#  1. bitwise the same on 1, 2 and 3 ranks: every CSV log byte for byte, every
#     grid's datasets by h5diff or tools/h5_same.py (the files' object times differ);
#  2. a run stopped at a checkpoint and restarted in its directory (on 1 and on
#     3 ranks) leaves the same logs and grid index as the uninterrupted run.
# usage: measurements.sh GRAINSTORM MPIEXEC SCENE WORKDIR
set -euo pipefail
gs=$1 mpiexec=$2 scene=$3 work=$4
tools=$(cd "$(dirname "$0")/../../tools" && pwd)
rm -rf "$work" && mkdir -p "$work" && cd "$work"
export OMP_NUM_THREADS=1 OMP_WAIT_POLICY=passive
mpi() { local np=$1; shift; "$mpiexec" --oversubscribe --allow-run-as-root -np "$np" "$gs" "$@"; }
fail() { echo "FAIL: $*" >&2; exit 1; }
# The grids compared by h5diff, or where HDF5's tools are absent (the GPU
# machines' image) by tools/h5_same.py with h5py.
same_h5=(h5diff)
if ! command -v h5diff > /dev/null; then
  python3 -c "import h5py" 2> /dev/null ||
    fail "neither h5diff (Debian package hdf5-tools, tools/install_deps.sh) nor Python's h5py is installed"
  same_h5=(python3 "$tools/h5_same.py")
fi
same_measurements() {  # reference directory, other directory, what
  local n=0
  for f in "$1"/flow_*.csv "$1"/average_*.csv "$1"/average_*.xdmf; do
    cmp "$f" "$2/$(basename "$f")" || fail "$3: $(basename "$f") differs"
    n=$((n + 1))
  done
  for f in "$1"/average_*.h5; do
    "${same_h5[@]}" "$f" "$2/$(basename "$f")" > /dev/null || fail "$3: $(basename "$f") differs"
    n=$((n + 1))
  done
  (( n >= 10 )) || fail "$3: only $n measurement files"
}

"$gs" run "$scene" --backend cpu --out one > one.log
for np in 2 3; do
  mpi $np run "$scene" --backend cpu --out "ranks$np" > "ranks$np.log"
  same_measurements one "ranks$np" "$np ranks"
done
# The mesh flow (a shallow pyramid, tests/cli/flow_tent.stl) counts spheres settling through it.
awk -F, '$4 == "all" && $5 == "all" {n = $12} END {exit !(n > 0)}' one/flow_tent.csv ||
  fail "the mesh flow tent counted no crossing"
echo "measurements on 1, 2, 3 ranks: bitwise equal"

# Stop at the uninterrupted run's older kept checkpoint (at 0.075 s; they
# come every 0.025 s): the flows sample every 0.01 and 0.015 s, so the
# restart falls between their samples.
stop=$(ls one/checkpoint_*.h5 | sort | head -1 | sed 's/.*checkpoint_0*\([0-9]*\)\.h5/\1/')
mpi 2 run "$scene" --backend cpu --steps "$stop" --out cut > cut.log
checkpoint=$(ls cut/checkpoint_*.h5 | sort | tail -1)
for np in 1 3; do
  cp -r cut "again$np"
  # What a run killed after its checkpoint had written: a row too many.
  tail -1 "again$np/flow_middle.csv" | awk -F, -v OFS=, '{$2 = $2 + 1; print}' >> "again$np/flow_middle.csv"
  mpi $np run "$scene" --backend cpu --restart "again$np/$(basename "$checkpoint")" --out "again$np" > "again$np.log"
  same_measurements one "again$np" "restart on $np ranks"
done
echo "measurements across a restart: bitwise equal"
