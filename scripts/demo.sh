#!/usr/bin/env bash
# The demo: install what is needed, build into ${BUILD_DIR:-build}, then compute the manifold
# harmonic basis of the Stanford bunny (Testing/Data/bunny.ply) and denoise a noisy copy of it.
# Writes demo-output/bunny_basis.vtp, demo-output/harmonics.png and demo-output/denoise.png, then
# the harmonics of a tetrahedral ball on slices (demo-output/volume-harmonic.png) and the bunny's
# points as a noisy point cloud, denoised (demo-output/denoised-cloud.png).
# Environment: BUILD_DIR (default build), JOBS (default 2), SKIP_DEPS=1 to skip install-deps.sh,
# OUTPUT (default demo-output).
set -euo pipefail

source_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${BUILD_DIR:-build}"
case "${build_dir}" in
  /*) ;;
  *) build_dir="${source_dir}/${build_dir}" ;;
esac
output="${OUTPUT:-${source_dir}/demo-output}"

if [ "${SKIP_DEPS:-0}" != 1 ]; then
  bash "${source_dir}/scripts/install-deps.sh"
fi

cmake -S "${source_dir}" -B "${build_dir}" \
  -DCMAKE_BUILD_TYPE=Release \
  -DMANIFOLDHARMONICS_USE_PARAVIEW=ON \
  -DParaView_DIR=/usr/lib/x86_64-linux-gnu/cmake/paraview-5.11
cmake --build "${build_dir}" -j "${JOBS:-2}"

# shellcheck disable=SC1091
. "${build_dir}/env.sh"
# Rendering needs an X server (Debian's VTK renders through GLX): use a virtual one if needed.
runner=()
if [ -z "${DISPLAY:-}" ]; then
  runner=(xvfb-run -a)
fi
"${runner[@]}" pvpython "${source_dir}/Examples/Python/demo.py" \
  "${source_dir}/Testing/Data/bunny.ply" "${output}"
"${runner[@]}" pvpython "${source_dir}/Examples/Python/volume_demo.py" "${output}"
"${runner[@]}" pvpython "${source_dir}/Examples/Python/cloud_demo.py" \
  "${source_dir}/Testing/Data/bunny.ply" "${output}"
