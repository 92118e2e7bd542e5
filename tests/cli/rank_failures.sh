#!/usr/bin/env bash
# An error on one rank in any phase of a run on 2 ranks (CTest, CPU ranks,
# MPMD launches with different arguments per rank) stops every rank within
# seconds with one message that names the rank and the cause, and a non-zero
# exit; before the run starts, nothing is written. Phases: the scene (missing
# on rank 1, on rank 0), the options (another scene, another --out, or a
# mesh file of other contents on rank 1), the restart
# checkpoint (missing on rank 1), the first step (a fault: logged in run.log,
# with the state written to fault_<step>.h5), and an output written mid-run
# (a snapshot rank 0 cannot write).
# usage: rank_failures.sh GRAINSTORM MPIEXEC SETTLE_SCENE FAULT_SCENE WORKDIR
set -euo pipefail
gs=$1 mpiexec=$2 scene=$3 fault_scene=$4 work=$5
rm -rf "$work" && mkdir -p "$work" && cd "$work"
export OMP_NUM_THREADS=1 OMP_WAIT_POLICY=passive
fail() { echo "FAIL: $*" >&2; exit 1; }
cp "$scene" s.yaml
steps=$(( $("$gs" check s.yaml | awk '/^steps:/ {print $2}') ))
quarter=$(( steps / 4 ))  # past the first checkpoint (every 0.05 s)

# Runs mpiexec with rank 0's and rank 1's arguments (separated by ::) under a
# 60 s limit; expects a non-zero exit and stderr with exactly one
# "grainstorm: error" or "grainstorm: run stopped" line that holds $expect.
expect_stopped() {
  local name=$1 expect=$2; shift 2
  local rank0=() rank1=()
  while [[ $1 != :: ]]; do rank0+=("$1"); shift; done
  shift
  rank1=("$@")
  set +e
  timeout 60 "$mpiexec" --oversubscribe --allow-run-as-root -np 1 "$gs" run "${rank0[@]}" --backend cpu \
    : -np 1 "$gs" run "${rank1[@]}" --backend cpu > "$name.out" 2> "$name.err"
  local code=$?
  set -e
  [[ $code != 124 ]] || fail "$name: still running after 60 s"
  [[ $code != 0 ]] || fail "$name: exit code 0"
  local lines
  lines=$(grep -c "^grainstorm: \(error\|run stopped\)" "$name.err" || true)
  [[ $lines == 1 ]] || fail "$name: $lines messages, expected one: $(cat "$name.err")"
  grep "^grainstorm: " "$name.err" | grep -qF -- "$expect" || fail "$name: the message lacks '$expect': $(cat "$name.err")"
  echo "$name: exit $code: $(grep "^grainstorm: " "$name.err")"
}
expect_nothing_written() { [[ ! -e $1 ]] || fail "$1 was written: $(ls "$1")"; }

expect_stopped scene1 "rank 1: /nonexistent/s.yaml" s.yaml --out scene1 :: /nonexistent/s.yaml --out scene1
expect_nothing_written scene1
expect_stopped scene0 "rank 0: /nonexistent/s.yaml" /nonexistent/s.yaml --out scene0 :: s.yaml --out scene0
expect_nothing_written scene0

sed 's/duration: 0.4/duration: 0.3/' s.yaml > other.yaml
expect_stopped options "rank 1: runs other.yaml" s.yaml --out options :: other.yaml --out options
expect_nothing_written options
expect_stopped outs "rank 1: runs s.yaml" s.yaml --out outs :: s.yaml --out outs2
expect_nothing_written outs
# The same scene text whose mesh file differs on rank 1 (a node-local copy):
# a flow surface one vertex of which moved by 0.1 mm.
mkdir -p mesh0 mesh1
cp "$(dirname "$scene")/measure_small.yaml" mesh0/m.yaml && cp "$(dirname "$scene")/flow_tent.stl" mesh0/
cp mesh0/m.yaml mesh1/m.yaml
awk '/vertex/ && !done { $2 += 1e-4; done = 1 } { print }' mesh0/flow_tent.stl > mesh1/flow_tent.stl
! cmp -s mesh0/flow_tent.stl mesh1/flow_tent.stl || fail "mesh: the STL copies are the same"
expect_stopped meshes "meshes read" mesh0/m.yaml --out meshes :: mesh1/m.yaml --out meshes
expect_nothing_written meshes

"$mpiexec" --oversubscribe --allow-run-as-root -np 2 "$gs" run s.yaml --backend cpu --steps $quarter --out first \
  > first.log
checkpoint=$(ls first/checkpoint_*.h5 | sort | head -1)
expect_stopped restart "rank 1: " s.yaml --restart "$checkpoint" --out restart :: \
  s.yaml --restart missing/checkpoint.h5 --out restart
grep -qF "missing/checkpoint.h5" restart.err || fail "restart: the message does not name the file: $(cat restart.err)"
expect_nothing_written restart

# The first step: one sphere leaves the domain; the fault is logged and the
# state it was found in is written.
expect_stopped fault "step 1: particle 1: the particle left the domain" "$fault_scene" --out fault :: \
  "$fault_scene" --out fault
grep -q "^rank [01]: step 1: particle 1: the particle left the domain\|run stopped by a fault: rank [01]: step 1" \
  fault/run.log || fail "fault: not in run.log: $(cat fault/run.log)"
snapshot=$(ls fault/fault_*.h5)
"$gs" info "$snapshot" > fault.info || fail "fault: $snapshot unreadable"
grep -q "^particles: *2$" fault.info || fail "fault: $snapshot: $(cat fault.info)"
grep -q "velocity" fault.info || fail "fault: $snapshot lacks the velocities: $(cat fault.info)"
# On one rank, the same.
set +e; "$gs" run "$fault_scene" --backend cpu --out fault1 > fault1.out 2> fault1.err; code=$?; set -e
[[ $code != 0 ]] || fail "fault on one rank: exit code 0"
grep -q "run stopped by a fault: step 1: particle 1: the particle left the domain" fault1/run.log ||
  fail "fault on one rank: not in run.log: $(cat fault1/run.log)"
ls fault1/fault_*.h5 > /dev/null || fail "fault on one rank: no fault snapshot"
echo "fault: logged, state written to $snapshot"

# Output mid-run: the snapshot after the restart step cannot be written (a
# directory holds its name); rank 0 fails alone, every rank stops.
cp -r first output
step=$(( 10#$(basename "$checkpoint" .h5 | sed 's/checkpoint_//') ))
blocked=$(ls first/particles_*.csv | sort | awk -F'[_.]' -v s=$step '$(NF-1) + 0 > s {print; exit}')
[[ -n $blocked ]] || fail "output: no snapshot after step $step in first/"
rm -f "output/$(basename "$blocked")" && mkdir "output/$(basename "$blocked")"
expect_stopped output "rank 0: " s.yaml --restart "$checkpoint" --out output :: s.yaml --restart "$checkpoint" --out output
grep -qF "$(basename "$blocked")" output.err || fail "output: the message does not name the file: $(cat output.err)"
grep -q "run stopped by an error: rank 0: .*$(basename "$blocked")" output/run.log || fail "output: not in run.log"
