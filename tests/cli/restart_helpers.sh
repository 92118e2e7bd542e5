# Sourced by the restart tests (restart.sh, edited_restart.sh) after they set
# gs, mpiexec, scene and work from their arguments: a fresh work directory
# to run in, one thread per rank, and their helpers.
rm -rf "$work" && mkdir -p "$work" && cd "$work"
export OMP_NUM_THREADS=1 OMP_WAIT_POLICY=passive
mpi() { local np=$1; shift; "$mpiexec" --oversubscribe --allow-run-as-root -np "$np" "$gs" "$@"; }
last_csv() { ls "$1"/particles_*.csv | sort | tail -1; }
fail() { echo "FAIL: $*" >&2; exit 1; }
