#!/usr/bin/env bash
# Checkpoint and restart through the command line (CTest, CPU-emulated ranks):
#  1. a run of 2N steps equals N steps + restart + N steps, bit for bit, on one
#     rank, and when the checkpoint written on 2 ranks restarts on 1 and on 3;
#  2. SIGTERM during a run leaves a checkpoint (exit code 3) that restarts to
#     the same end state;
#  3. a truncated checkpoint is refused with a clear message, and the previous
#     checkpoint still restarts.
# usage: restart.sh GRAINSTORM MPIEXEC SCENE WORKDIR
set -euo pipefail
gs=$1 mpiexec=$2 scene=$3 work=$4
source "$(dirname "${BASH_SOURCE[0]}")/restart_helpers.sh"

steps=$(( $("$gs" check "$scene" | awk '/^steps:/ {print $2}') ))
half=$(( steps / 2 ))
"$gs" run "$scene" --backend cpu --out full > full.log
reference=$(last_csv full)

# 1. Checkpoints land every 0.05 s; restart from the one nearest the middle.
mpi 2 run "$scene" --backend cpu --steps "$half" --out first > first.log
checkpoint=$(ls first/checkpoint_*.h5 | sort | tail -1)
[[ -f $checkpoint ]] || fail "no checkpoint written"
for np in 1 3; do
  mpi $np run "$scene" --backend cpu --restart "$checkpoint" --out "again$np" > "again$np.log" 2> "again$np.err"
  cmp "$reference" "$(last_csv again$np)" || fail "restart on $np ranks differs from the uninterrupted run"
  # One progress line for the last step, from rank 0 only.
  [[ $(grep -c "^step $steps/$steps " "again$np.err") == 1 ]] || fail "progress on $np ranks: $(cat again$np.err)"
done
"$gs" run "$scene" --backend cpu --restart "$checkpoint" --out again1b > /dev/null
echo "restart across rank counts: bitwise equal"

# 2. SIGTERM: the run checkpoints, says so and exits with 3.
"$gs" run "$scene" --backend cpu --out term > term.log 2>&1 &
pid=$!
# Signal it as soon as it steps: a fast machine runs a small scene in well
# under a second.
for _ in $(seq 1000); do grep -qs "set up in" term/run.log && break; sleep 0.01; done
kill -TERM $pid 2>/dev/null || fail "SIGTERM: the run had ended before the signal"

set +e; wait $pid; code=$?; set -e
[[ $code == 3 ]] || fail "SIGTERM: exit code $code, expected 3"
grep -q "stopped by a signal" term/run.log || fail "SIGTERM: no message in the log"
saved=$(ls term/checkpoint_*.h5 | sort | tail -1)
"$gs" run "$scene" --backend cpu --restart "$saved" --out term > /dev/null
cmp "$reference" "$(last_csv term)" || fail "restart after SIGTERM differs"
echo "SIGTERM checkpoint restarts: bitwise equal"

# 3. A truncated checkpoint is refused; the previous one still works.
cp "$checkpoint" cut.h5
truncate -s $(( $(stat -c %s cut.h5) / 2 )) cut.h5
set +e; "$gs" run "$scene" --backend cpu --restart cut.h5 --out cut > cut.log 2> cut.err; code=$?; set -e
[[ $code != 0 ]] || fail "truncated checkpoint accepted"
grep -q "cut.h5" cut.err || fail "the refusal does not name the file: $(cat cut.err)"
[[ ! -e cut ]] || fail "a refused restart wrote output"
"$gs" run "$scene" --backend cpu --restart "$checkpoint" --steps $(( half + 10 )) --out still > /dev/null
echo "truncated checkpoint refused: $(head -c 200 cut.err)"
