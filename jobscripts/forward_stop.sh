#!/bin/bash
# Runs an mpirun/mpiexec command line and turns SIGTERM (and SIGUSR1, SIGINT)
# to this script into SIGUSR1 to mpirun. Open MPI's mpirun forwards SIGUSR1 to
# every rank at once, and grainstorm then writes a checkpoint and exits with code 3,
# which mpirun returns. A SIGTERM to mpirun itself instead makes it forward
# SIGTERM only after odls_base_sigkill_timeout seconds (default 1), kill the
# ranks after as many again, and exit with 1 whatever the ranks return.
#   jobscripts/forward_stop.sh mpirun -np 4 build/src/grainstorm run scene.yaml
# Some Open MPI builds do not forward SIGUSR1 (seen: Ubuntu 24.04's 4.1.6), so
# the ranks mpirun started on this host (its children) get SIGUSR1 directly
# as well; a rank that hears it twice stops once. Ranks on other hosts need
# mpirun's forwarding (or srun, which passes signals to every task).
# Exits with the command's own code.
set -uo pipefail
"$@" &
pid=$!
stop() {
  kill -USR1 $pid 2>/dev/null
  pkill -USR1 -P $pid 2>/dev/null
}
trap stop TERM USR1 INT
# `wait` returns early (with 128 + signal) when a trapped signal arrives:
# wait again until the command itself has ended, then once more for its own
# code (bash keeps the status of a child it has reaped; a command that ended
# just as the signal came would otherwise leave 128 + signal).
while kill -0 $pid 2>/dev/null; do
  wait $pid
done
wait $pid
exit $?
