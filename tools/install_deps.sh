#!/usr/bin/env bash
# Installs what grainstorm needs to build and test on Debian/Ubuntu (run as
# root or with sudo available). The CUDA toolkit is not installed here: the
# CUDA backend is built when nvcc is found (PATH or /usr/local/cuda/bin).
# python3-h5py and python3-matplotlib serve the Python tools (tools/render_topview.py,
# tools/plot_mixing.py, bench/plot_accuracy.py) and their tests.
set -euo pipefail
packages=(build-essential cmake git libyaml-cpp-dev libgtest-dev googletest libopenmpi-dev openmpi-bin
          libhdf5-dev hdf5-tools libmetis-dev python3 python3-numpy python3-h5py python3-matplotlib
          python3-paraview)
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  echo "install_deps: all packages present"
  exit 0
fi
sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
