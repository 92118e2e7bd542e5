#!/usr/bin/env bash
# Set-up time and peak host memory of a run of a frictional lattice bed of N
# touching spheres (as bench/scaling_bed.sh builds it, square base, twice as
# tall as wide; bench/lattice_bed.sh) on R ranks, each free to use every core
# (--bind-to none: mpirun's default binds a rank to one core, and the set-up's
# threads would share it). The run is stopped (SIGKILL) once it has printed
# its set-up line: what follows, the first snapshot, is not set-up.
#   bench/setup_time.sh BUILD_DIR N [RANKS=1] [BACKEND=cuda] [OUTDIR=/tmp/setup_time]
# Prints the run's "set up in" and "host threads" lines and each rank's peak
# resident memory.
set -euo pipefail
build=$1 count=$2 ranks=${3:-1} backend=${4:-cuda} out=${5:-/tmp/setup_time}
mkdir -p "$out"
py() { python3 -c "print($1)"; }
side=$(py "round(($count / 2) ** (1/3))")
layers=$(py "round($count / $side**2)")
scene=$out/bed_$count.yaml
"$(dirname "$0")/lattice_bed.sh" "$side" "$layers" "$out/run_$count" id > "$scene"
log=$out/setup_$count.log
mpiexec --allow-run-as-root --oversubscribe --bind-to none -n "$ranks" \
  /usr/bin/time -f "rank peak resident memory %M kB" \
  "$build/src/grainstorm" run "$scene" --backend "$backend" --steps 1 --overwrite > "$log" 2>&1 &
while kill -0 $! 2>/dev/null && ! grep -q "host threads" "$log"; do sleep 0.2; done
pkill -KILL -f "^$build/src/grainstorm run $scene" || true  # not mpiexec or time, which report
wait || true
grep -E "particles,|set up in|host threads|peak resident|rror" "$log"
