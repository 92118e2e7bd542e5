# Sourced by the device scripts. use_carried_deps ROOT: where ROOT/carry/root/usr
# holds Debian's METIS and yaml-cpp unpacked (a GPU machine without them;
# bench/device_session.sh says how to fill it), points CMake and the loader
# at them and sets the array `extra` to the CMake arguments that name METIS;
# else `extra` is empty. Puts the CUDA toolkit's bin on PATH.
use_carried_deps() {
  local usr=$1/carry/root/usr
  extra=()
  if [[ -d $usr ]]; then
    export CMAKE_PREFIX_PATH=$usr
    export LD_LIBRARY_PATH=$usr/lib/x86_64-linux-gnu:${LD_LIBRARY_PATH:-}
    extra=(-DMETIS_INCLUDE_DIR=$usr/include -DMETIS_LIBRARY=$usr/lib/x86_64-linux-gnu/libmetis.so)
  fi
  export PATH=/usr/local/cuda/bin:$PATH
}
