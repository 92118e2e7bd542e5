#!/bin/bash
# One host with several GPUs, no scheduler: one rank per GPU.
#   jobscripts/single_host.sh SCENE [grainstorm options]
set -euo pipefail
scene=${1:?usage: jobscripts/single_host.sh SCENE [grainstorm options]}
shift
gpus=$(nvidia-smi -L 2>/dev/null | grep -c '^GPU ' || true)  # whole GPUs (not their MIG lines)
((gpus > 0)) || { echo "single_host.sh: no GPU found by nvidia-smi -L" >&2; exit 1; }
cores=$(nproc)
export OMP_NUM_THREADS=$(( cores / gpus > 0 ? cores / gpus : 1 ))
# SIGTERM or SIGUSR1 to this script reaches every rank at once as SIGUSR1
# (jobscripts/forward_stop.sh): a checkpoint, and exit code 3. A SIGTERM sent
# to mpirun itself reaches the ranks only after odls_base_sigkill_timeout
# seconds, with as many again before they are killed; 10 s leaves time for the
# checkpoint (mpirun then exits with 1).
export OMPI_MCA_odls_base_sigkill_timeout=${OMPI_MCA_odls_base_sigkill_timeout:-10}
exec jobscripts/forward_stop.sh mpirun -np "$gpus" --bind-to none -x OMP_NUM_THREADS \
  build/src/grainstorm run "$scene" --backend cuda "$@"
