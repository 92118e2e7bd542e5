#!/usr/bin/env bash
# A CUDA timeline of one command (kernels, copies, runtime API calls with
# their times), where Nsight Systems is not at hand: builds the CUPTI
# injection library bench/gpu_trace/gpu_trace.cpp and runs the command under
# it; then summarise with bench/gpu_timeline.py.
#   TRACE=trace.csv bench/gpu_trace.sh COMMAND [ARGS...]
# CUDA: $CUDA_HOME (default /usr/local/cuda), its include/ and lib64/ (or lib/) holding CUPTI.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cuda=${CUDA_HOME:-/usr/local/cuda}
lib=${TRACE_LIB:-/tmp/libgs_gpu_trace.so}
libdir=$cuda/lib64
[[ -e $libdir/libcupti.so ]] || libdir=$cuda/lib
[[ -e $libdir/libcupti.so ]] || libdir=$cuda/extras/CUPTI/lib64
inc=$cuda/include
[[ -e $inc/cupti.h ]] || inc=$cuda/extras/CUPTI/include
if [[ ! -e $lib || $root/bench/gpu_trace/gpu_trace.cpp -nt $lib ]]; then
  g++ -O2 -std=c++17 -shared -fPIC -I"$inc" "$root/bench/gpu_trace/gpu_trace.cpp" -L"$libdir" -lcupti \
    -Wl,-rpath,"$libdir" -o "$lib"
fi
export GS_TRACE_FILE=${TRACE:-$(pwd)/gpu_trace.csv}
CUDA_INJECTION64_PATH=$lib exec "$@"
