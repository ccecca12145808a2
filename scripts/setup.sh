#!/usr/bin/env bash
# Installs what vaegail needs from Debian's packages (bookworm), then configures and builds.
# Safe to re-run: installs only what is missing and rebuilds incrementally.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake pkg-config
  libtorch-dev            # LibTorch 1.13 C++ frontend
  libmujoco-dev libqhull-dev  # MuJoCo 2.2 C API (its CMake target names qhull's headers)
  libhdf5-dev             # demonstration files
  libopenblas0-openmp     # BLAS for LibTorch: ~8x faster LSTMs than the reference BLAS
  libcli11-dev nlohmann-json3-dev
  libfmt-dev              # fmt 9: type-safe text formatting without fixed buffers (docs/architecture.md)
  libgtest-dev libbenchmark-dev
  libegl-dev libegl-mesa0 libgl-dev libgl1-mesa-dri  # render: OpenGL without display or GPU (EGL surfaceless, llvmpipe)
  libavcodec-dev libavformat-dev libswscale-dev       # render: H.264 (libx264) in MP4
  python3-h5py python3-numpy  # tests: fixtures in the layouts of h5py, Minari and imitation
  openmpi-bin libopenmpi-dev  # `mpirun -np K vaegail gail|experts train`: one run on K processes (util/world.h)
  python3-matplotlib      # figures: scripts/plot/ draws the CSV files vaegail writes
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  as_root=()
  [[ $(id -u) -eq 0 ]] || as_root=(sudo)
  "${as_root[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# LibTorch calls whatever BLAS update-alternatives selects; make sure it is OpenBLAS.
openblas=/usr/lib/x86_64-linux-gnu/openblas-openmp
if [[ -e $openblas/libblas.so.3 ]] && ! readlink -f /usr/lib/x86_64-linux-gnu/libblas.so.3 | grep -q openblas; then
  as_root=()
  [[ $(id -u) -eq 0 ]] || as_root=(sudo)
  "${as_root[@]}" update-alternatives --set libblas.so.3-x86_64-linux-gnu $openblas/libblas.so.3
  "${as_root[@]}" update-alternatives --set liblapack.so.3-x86_64-linux-gnu $openblas/liblapack.so.3
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DVAEGAIL_STAGES="util;env;data;rl;experts;vae;gail;eval;render;bench;cli;controller" >/dev/null
cmake --build build -j"$(nproc)"
