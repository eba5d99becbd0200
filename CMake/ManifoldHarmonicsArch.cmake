# The instruction set the spectral core is compiled for (the one home of this rule, included by
# the top-level CMakeLists.txt and by the core's own test project, Testing/Core).
#
# The eigensolver's dense kernels (Eigen) are several times faster with the build machine's
# vector instructions (AVX2/AVX-512) than with the x86-64 baseline, so the default is the build
# machine's ("native"). "x86-64" builds binaries for any x86-64 machine (and is what
# scripts/check-portability.sh compares with "native"); "x86-64-v2", "-v3", "-v4" are the
# micro-architecture levels in between; an empty value leaves the compiler's default.
# MANIFOLDHARMONICS_CORE_COMPILE_OPTIONS holds the resulting flags (empty for other compilers).
set(MANIFOLDHARMONICS_ARCH "native"
  CACHE STRING "Instruction set of the spectral core: native, x86-64, x86-64-v2, x86-64-v3, x86-64-v4 or empty (the compiler's default)")
set_property(CACHE MANIFOLDHARMONICS_ARCH
  PROPERTY
    STRINGS "native" "x86-64" "x86-64-v2" "x86-64-v3" "x86-64-v4" "")
set(MANIFOLDHARMONICS_CORE_COMPILE_OPTIONS "")
if (MANIFOLDHARMONICS_ARCH AND CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
  set(MANIFOLDHARMONICS_CORE_COMPILE_OPTIONS "-march=${MANIFOLDHARMONICS_ARCH}")
endif ()
