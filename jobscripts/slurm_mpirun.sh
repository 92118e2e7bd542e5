#!/bin/bash
# Slurm, several nodes x 4 GPUs, one rank per GPU launched by Open MPI's mpirun.
#   sbatch --nodes=2 jobscripts/slurm_mpirun.sh cases/demo/settle.yaml
#SBATCH --job-name=grainstorm
#SBATCH --ntasks-per-node=4
#SBATCH --gpus-per-node=4
#SBATCH --cpus-per-task=8
#SBATCH --time=24:00:00
#SBATCH --signal=B:USR1@300
set -euo pipefail
scene=${1:?usage: sbatch jobscripts/slurm_mpirun.sh SCENE [grainstorm options]}
shift
export OMP_NUM_THREADS=$SLURM_CPUS_PER_TASK
# The batch shell gets USR1 five minutes before the limit (B:), and
# forward_stop.sh passes it (or a SIGTERM sent to the shell alone) to mpirun as
# USR1, which Open MPI forwards to every rank at once: grainstorm writes a
# checkpoint and exits with code 3, and so does this script. At the limit, or
# on scancel, Slurm sends SIGTERM to mpirun itself: Open MPI then passes
# SIGTERM to the ranks after odls_base_sigkill_timeout seconds and kills them
# after as many again, and exits with 1. The ranks stop within two steps of
# the signal; 10 s leaves the checkpoint time to be written, within Slurm's
# KillWait (30 s by default).
export OMPI_MCA_odls_base_sigkill_timeout=${OMPI_MCA_odls_base_sigkill_timeout:-10}
exec jobscripts/forward_stop.sh mpirun --map-by ppr:4:node:PE=$SLURM_CPUS_PER_TASK --bind-to core -x OMP_NUM_THREADS \
  build/src/grainstorm run "$scene" --backend cuda "$@"
