#!/usr/bin/env bash
# Build and test Manifold Harmonics three times:
#   1. against ParaView (module, Python wrapping, plugin) in ${BUILD_DIR:-build}, all tests;
#   2. as a plain VTK module (find_package(VTK), no ParaView) in ${BUILD_DIR}/vtk-only: the module,
#      its Python wrapping, the C++ test driver and the examples must build against plain VTK; its
#      tests run but the C++ filter cases (label FiltersCxx: the same code on the same VTK
#      libraries as in stage 1, which runs them); the Python test and the examples run in the
#      plain Python interpreter instead of pvpython. The VTK-free core is not compiled again: the
#      module links stage 1's core library (MANIFOLDHARMONICS_SPECTRAL_CORE_FROM); the core's
#      tests and the benchmark program are left out (stages 1 and 3 have them);
#   3. the spectral core alone (Testing/Core, no VTK) with AddressSanitizer and
#      UndefinedBehaviorSanitizer in ${BUILD_DIR}/sanitize, for the x86-64 baseline (stage 1 builds
#      it for this machine's CPU), its tests but the slow ones, then the libFuzzer target
#      FuzzCore for FUZZ_SECONDS (default 30: the CI budget; longer runs by hand) when clang is
#      available.
# Exits non-zero if a dependency, a configure, a build, a test or the fuzzer fails.
# Environment: BUILD_DIR (default build), JOBS (default 2), SKIP_DEPS=1 to skip install-deps.sh,
# FUZZ_SECONDS (0 skips the fuzzer), SKIP_SANITIZE=1 to skip stage 3, EXCLUDE_LABELS (a CTest
# label regular expression the tests of stages 1 and 2 leave out, e.g. 'slow|mpi' for a quick
# run: labels slow, the long solves, and mpi, the runs under mpiexec; default none).
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

# CTest's -LE for stages 1 and 2: EXCLUDE_LABELS and the stage's own.
exclude ()
{
  local labels="${EXCLUDE_LABELS:-}"
  if [ -n "$1" ]; then
    labels="${labels:+${labels}|}$1"
  fi
  if [ -n "${labels}" ]; then
    printf '%s\n' -LE "${labels}"
  fi
}

echo "=== ParaView build: ${build_dir}"
cmake -S "${source_dir}" -B "${build_dir}" \
  -DCMAKE_BUILD_TYPE=Release \
  -DBUILD_TESTING=ON \
  -DMANIFOLDHARMONICS_USE_PARAVIEW=ON \
  -DParaView_DIR="${cmake_dir}"
cmake --build "${build_dir}" -j "${jobs}"
mapfile -t stage_labels < <(exclude "")
(cd "${build_dir}" && run_ctest --output-on-failure -j "${jobs}" "${stage_labels[@]}") || status=1

echo "=== Plain VTK build: ${build_dir}/vtk-only"
cmake -S "${source_dir}" -B "${build_dir}/vtk-only" \
  -DCMAKE_BUILD_TYPE=Release \
  -DBUILD_TESTING=ON \
  -DMANIFOLDHARMONICS_USE_PARAVIEW=OFF \
  -DMANIFOLDHARMONICS_CORE_TESTS=OFF \
  -DMANIFOLDHARMONICS_BUILD_BENCH=OFF \
  -DMANIFOLDHARMONICS_SPECTRAL_CORE_FROM="${build_dir}/Filters/Spectral" \
  -DVTK_DIR="${cmake_dir}/vtk"
cmake --build "${build_dir}/vtk-only" -j "${jobs}"
mapfile -t stage_labels < <(exclude FiltersCxx)
(cd "${build_dir}/vtk-only" && run_ctest --output-on-failure -j "${jobs}" "${stage_labels[@]}") ||
  status=1

if [ "${SKIP_SANITIZE:-0}" != 1 ]; then
  sanitize_dir="${build_dir}/sanitize"
  fuzz_seconds="${FUZZ_SECONDS:-30}"
  # libFuzzer needs clang; without it the sanitized tests still run with the default compiler.
  if command -v clang++ > /dev/null 2>&1; then
    sanitize_compiler=(-DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++
      -DMANIFOLDHARMONICS_FUZZ=ON)
  else
    sanitize_compiler=(-DMANIFOLDHARMONICS_FUZZ=OFF)
    fuzz_seconds=0
  fi
  # Line tables only (-g1): enough for the sanitizers' reports, and a quarter less compile
  # time than -g (clang, FunctionalMap.cxx: 24 s against 32 s).
  sanitize_flags="-O2 -g1 -DNDEBUG"
  echo "=== Core with sanitizers: ${sanitize_dir}"
  stage_start=${SECONDS}
  cmake -S "${source_dir}/Testing/Core" -B "${sanitize_dir}" \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="${sanitize_flags}" \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="${sanitize_flags}" \
    -DMANIFOLDHARMONICS_SANITIZE=ON \
    -DMANIFOLDHARMONICS_ARCH=x86-64 \
    "${sanitize_compiler[@]}"
  cmake --build "${sanitize_dir}" -j "${jobs}"
  # CHOLMOD and OpenBLAS are not instrumented: leaks inside them are not ours to report.
  export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:detect_leaks=0"
  export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
  # Labels (Testing/Core/CMakeLists.txt): "slow" solves take minutes under the sanitizers and run
  # optimized in stage 1, as do the "portability" reruns of the counting tests.
  (cd "${sanitize_dir}" && ctest --output-on-failure -j "${jobs}" -LE 'slow|portability') ||
    status=1
  if [ "${fuzz_seconds}" -gt 0 ]; then
    echo "=== Fuzzing the core for ${fuzz_seconds} s"
    mkdir -p "${sanitize_dir}/fuzz-corpus" "${sanitize_dir}/fuzz-findings"
    # Testing/Core/fuzz-regressions: inputs that once failed, run first as part of the corpus.
    (cd "${sanitize_dir}/fuzz-findings" && OPENBLAS_NUM_THREADS=1 \
      "${sanitize_dir}/FuzzCore" -seed=1 -max_total_time="${fuzz_seconds}" -max_len=512 \
      -timeout=20 -rss_limit_mb=2048 -print_final_stats=1 "${sanitize_dir}/fuzz-corpus" \
      "${source_dir}/Testing/Core/fuzz-regressions") || status=1
  fi
  echo "=== Sanitizer stage took $((SECONDS - stage_start)) s"
fi

if [ "${status}" -ne 0 ]; then
  echo "=== FAILED: see the CTest output above" >&2
else
  echo "=== All builds and tests passed"
fi
exit "${status}"
