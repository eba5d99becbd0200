#!/usr/bin/env bash
# Build and test Manifold Harmonics twice:
#   1. against ParaView (module, Python wrapping, plugin) in ${BUILD_DIR:-build}, all tests;
#   2. as a plain VTK module (find_package(VTK), no ParaView) in ${BUILD_DIR}/vtk-only, its tests.
# Exits non-zero if a dependency, a configure, a build or a test fails.
# Environment: BUILD_DIR (default build), JOBS (default 2), SKIP_DEPS=1 to skip install-deps.sh.
set -euo pipefail

source_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${BUILD_DIR:-build}"
case "${build_dir}" in
  /*) ;;
  *) build_dir="${source_dir}/${build_dir}" ;;
esac
jobs="${JOBS:-2}"
cmake_dir=/usr/lib/x86_64-linux-gnu/cmake/paraview-5.11

if [ "${SKIP_DEPS:-0}" != 1 ]; then
  bash "${source_dir}/scripts/install-deps.sh"
fi

# Rendering tests need an X server (GLX); run CTest inside a virtual one when there is none.
run_ctest ()
{
  if [ -z "${DISPLAY:-}" ] && command -v xvfb-run > /dev/null 2>&1; then
    xvfb-run -a ctest "$@"
  else
    ctest "$@"
  fi
}

status=0

echo "=== ParaView build: ${build_dir}"
cmake -S "${source_dir}" -B "${build_dir}" \
  -DCMAKE_BUILD_TYPE=Release \
  -DBUILD_TESTING=ON \
  -DMANIFOLDHARMONICS_USE_PARAVIEW=ON \
  -DParaView_DIR="${cmake_dir}"
cmake --build "${build_dir}" -j "${jobs}"
(cd "${build_dir}" && run_ctest --output-on-failure) || status=1

echo "=== Plain VTK build: ${build_dir}/vtk-only"
cmake -S "${source_dir}" -B "${build_dir}/vtk-only" \
  -DCMAKE_BUILD_TYPE=Release \
  -DBUILD_TESTING=ON \
  -DMANIFOLDHARMONICS_USE_PARAVIEW=OFF \
  -DVTK_DIR="${cmake_dir}/vtk"
cmake --build "${build_dir}/vtk-only" -j "${jobs}"
(cd "${build_dir}/vtk-only" && run_ctest --output-on-failure) || status=1

if [ "${status}" -ne 0 ]; then
  echo "=== FAILED: see the CTest output above" >&2
else
  echo "=== All builds and tests passed"
fi
exit "${status}"
