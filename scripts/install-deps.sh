#!/usr/bin/env bash
# Install the Debian 12 packages needed to build and test Manifold Harmonics.
# Idempotent: packages already installed are skipped (apt-get itself is not even called).
# Runs as root directly, or through sudo otherwise.
set -euo pipefail

packages=(
  paraview
  paraview-dev
  python3-paraview
  libeigen3-dev
  libspectra-dev
  libsuitesparse-dev
  libopenblas-dev
  cmake
  g++
  clang
  libclang-rt-14-dev
  xvfb
  xauth
  libgl1-mesa-dri
  libqt5svg5
  mpi-default-bin
  mpi-default-dev
  # The optional SLEPc solver (pulls libpetsc-real3.18-dev with MUMPS) and pkg-config, which
  # finds it.
  libslepc-real-dev
  pkg-config
  python3-scipy
  # The benchmark's SLEPc peer (bench/slepc_reference.py).
  python3-slepc4py
  python3-numpy
  libutfcpp-dev
  libavcodec-dev
  libavformat-dev
  libavutil-dev
  libswscale-dev
  libswresample-dev
  libpng-dev
  libx11-dev
  libpython3-dev
  libglew-dev
  libgl-dev
  libexpat1-dev
  liblzma-dev
  liblz4-dev
  libdouble-conversion-dev
  zlib1g-dev
)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "${package}" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("${package}")
  fi
done

if [ "${#missing[@]}" -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages are installed"
  exit 0
fi

if [ "$(id -u)" -eq 0 ]; then
  as_root=()
elif command -v sudo > /dev/null 2>&1; then
  as_root=(sudo)
else
  echo "install-deps: missing packages (${missing[*]}) and neither root nor sudo" >&2
  exit 1
fi

echo "install-deps: installing ${missing[*]}"
"${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update
"${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
  "${packages[@]}"
