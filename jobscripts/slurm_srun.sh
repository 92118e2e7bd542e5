#!/bin/bash
# Slurm, several nodes x 4 GPUs, one rank per GPU launched by srun.
#   sbatch --nodes=2 jobscripts/slurm_srun.sh cases/demo/settle.yaml
#SBATCH --job-name=grainstorm
#SBATCH --ntasks-per-node=4
#SBATCH --gpus-per-node=4
#SBATCH --cpus-per-task=8
#SBATCH --time=24:00:00
#SBATCH --signal=USR1@300
# USR1 to every task five minutes before the limit: grainstorm writes a checkpoint and exits
# with code 3; resubmit with --restart out/<dir>/checkpoint_<step>.h5.
set -euo pipefail
scene=${1:?usage: sbatch jobscripts/slurm_srun.sh SCENE [grainstorm options]}
shift
export OMP_NUM_THREADS=$SLURM_CPUS_PER_TASK
# Each rank sees all GPUs of its node and binds to local rank mod GPUs itself.
# srun is given the cores per task again: since Slurm 22.05 it does not take
# sbatch's --cpus-per-task, and each task would get one core for its threads.
srun --cpus-per-task="$SLURM_CPUS_PER_TASK" --cpu-bind=cores build/src/grainstorm run "$scene" --backend cuda "$@"
