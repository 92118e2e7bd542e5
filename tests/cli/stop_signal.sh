#!/usr/bin/env bash
# A stop signal to a run on 2 ranks under a real mpiexec (CTest, CPU ranks):
#  1. SIGTERM to mpiexec: Open MPI forwards it to the ranks after
#     odls_base_sigkill_timeout seconds (3 here; the jobscripts set 10) and
#     kills them after as many again. The checkpoint must be complete by then:
#     the stop flag is read every step, not after a chunk of up to 200 steps
#     (here 200 steps take about 10 s). mpiexec itself exits 1 after a SIGTERM,
#     whatever the ranks return (Open MPI's behaviour).
#  2. SIGUSR1 to mpiexec, which forwards it at once: exit code 3.
#  3. SIGTERM to jobscripts/forward_stop.sh around mpiexec: exit code 3.
# Each checkpoint is complete (grainstorm info) and restarts.
# usage: stop_signal.sh GRAINSTORM MPIEXEC SCENE WORKDIR JOBSCRIPTS
set -euo pipefail
gs=$1 mpiexec=$2 scene=$3 work=$4 jobscripts=$5
rm -rf "$work" && mkdir -p "$work" && cd "$work"
export OMP_NUM_THREADS=1 OMP_WAIT_POLICY=passive
mpi=("$mpiexec" --oversubscribe --allow-run-as-root -np 2)
fail() { echo "FAIL: $*" >&2; exit 1; }

# Starts a run into $1 with the launcher in the remaining words, waits until
# its first snapshot is written (the time loop begins), sends $signal to the
# launcher and waits for it (at most 60 s): sets $code.
stop_run() {
  local out=$1; shift
  timeout 120 "$@" "$gs" run "$scene" --backend cpu --out "$out" > "$out.log" 2>&1 &
  local pid=$!
  for _ in $(seq 600); do [[ -e $out/particles_0000000000.h5 ]] && break; sleep 0.1; done
  [[ -e $out/particles_0000000000.h5 ]] || fail "$out: the run did not start: $(tail -5 "$out.log")"
  # timeout runs the launcher as its child: signal that.
  local launcher
  launcher=$(pgrep -P $pid | head -1)
  kill -"$signal" "$launcher"
  set +e; wait $pid; code=$?; set -e
  [[ $code != 124 ]] || fail "$out: still running 120 s after the signal"
}

# The log names the stop step; that step's checkpoint is complete and restarts.
expect_checkpoint() {
  local out=$1
  grep -q "stopped by a signal" "$out/run.log" || fail "$out: no stop in the log: $(tail -5 "$out.log")"
  local step
  step=$(sed -n 's/^stopped by a signal at step \([0-9]*\) .*/\1/p' "$out/run.log")
  local checkpoint
  checkpoint=$(printf '%s/checkpoint_%010d.h5' "$out" "$step")
  [[ -f $checkpoint ]] || fail "$out: no checkpoint at the stop step $step: $(ls "$out")"
  "$gs" info "$checkpoint" > "$out.info"
  grep -q "integrity: *complete" "$out.info" || fail "$out: checkpoint not complete: $(cat "$out.info")"
  "${mpi[@]}" "$gs" run "$scene" --backend cpu --restart "$checkpoint" --steps $(( step + 2 )) --out "$out" \
    > "$out.restart.log" 2>&1 || fail "$out: the checkpoint does not restart: $(tail -5 "$out.restart.log")"
  echo "$out: stopped at step $step, checkpoint complete and restarts"
}

signal=TERM stop_run term "${mpi[@]}" --mca odls_base_sigkill_timeout 3
echo "SIGTERM to mpiexec: exit code $code"
[[ $code != 0 ]] || fail "SIGTERM to mpiexec: exit code 0"
expect_checkpoint term

# Does this mpiexec forward SIGUSR1 at all? Some builds do not (seen: Ubuntu
# 24.04's Open MPI 4.1.6); there only forward_stop.sh's direct signal to the
# local ranks stops a run at once.
printf '#!/bin/bash\ntrap "exit 3" USR1\nfor i in $(seq 100); do sleep 0.1; done\n' > probe.sh && chmod +x probe.sh
"${mpi[@]}" ./probe.sh > probe.log 2>&1 &
probe=$!
sleep 2
kill -USR1 $probe
set +e; wait $probe; probe_code=$?; set -e
if [[ $probe_code == 3 ]]; then
  signal=USR1 stop_run usr1 "${mpi[@]}"
  [[ $code == 3 ]] || fail "SIGUSR1 to mpiexec: exit code $code, expected 3: $(tail -5 usr1.log)"
  expect_checkpoint usr1
else
  echo "this mpiexec does not forward SIGUSR1 (probe exit code $probe_code): SIGUSR1 to mpiexec not tested"
fi

signal=TERM stop_run wrapped "$jobscripts/forward_stop.sh" "${mpi[@]}"
[[ $code == 3 ]] || fail "SIGTERM to forward_stop.sh: exit code $code, expected 3: $(tail -5 wrapped.log)"
expect_checkpoint wrapped
