# Sourced by bench scripts. start_mps DIR starts a CUDA MPS daemon of our own
# (pipe and log directories under DIR) and quits it when the script exits, so
# that processes sharing one GPU run their kernels at once instead of taking
# turns by time slices: on one H200, three runs of mixer case a side by side
# each ran at 2.6e7 particle-steps/s with MPS and 9.0e6 without
# (docs/PERFORMANCE.md, "Small scenes side by side"). Returns 1, leaving the
# GPU as it was, where the daemon did not start.
start_mps() {
  export CUDA_MPS_PIPE_DIRECTORY=$1/mps_pipe CUDA_MPS_LOG_DIRECTORY=$1/mps_log
  mkdir -p "$CUDA_MPS_PIPE_DIRECTORY" "$CUDA_MPS_LOG_DIRECTORY" || return 1
  if ! nvidia-cuda-mps-control -d; then
    unset CUDA_MPS_PIPE_DIRECTORY CUDA_MPS_LOG_DIRECTORY
    return 1
  fi
  trap 'echo quit | nvidia-cuda-mps-control' EXIT
}
