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
# The batch shell gets USR1 (B:) and passes it to mpirun, which forwards it to
# every rank: grainstorm checkpoints and exits with code 3.
mpirun --map-by ppr:4:node:PE=$SLURM_CPUS_PER_TASK --bind-to core -x OMP_NUM_THREADS \
  build/src/grainstorm run "$scene" --backend cuda "$@" &
pid=$!
trap 'kill -USR1 $pid' USR1
wait $pid || wait $pid
