#!/bin/bash
# One host with several GPUs, no scheduler: one rank per GPU.
#   jobscripts/single_host.sh SCENE [grainstorm options]
set -euo pipefail
scene=${1:?usage: jobscripts/single_host.sh SCENE [grainstorm options]}
shift
gpus=$(nvidia-smi -L | wc -l)
cores=$(nproc)
export OMP_NUM_THREADS=$(( cores / gpus > 0 ? cores / gpus : 1 ))
exec mpirun -np "$gpus" --bind-to none -x OMP_NUM_THREADS build/src/grainstorm run "$scene" --backend cuda "$@"
