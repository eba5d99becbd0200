# Source this file to use a build tree from pvpython, pvbatch, paraview or python3:
#   . scripts/env.sh [build directory, default: build]
# It sources <build>/env.sh, written by CMake, which sets PV_PLUGIN_PATH (the plugin loads
# automatically), PYTHONPATH (import manifoldharmonics) and LD_LIBRARY_PATH.
_manifoldharmonics_build="${1:-build}"
case "${_manifoldharmonics_build}" in
  /*) ;;
  *)
    if [ -n "${BASH_SOURCE:-}" ]; then
      _manifoldharmonics_build="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/${_manifoldharmonics_build}"
    fi
    ;;
esac
if [ -f "${_manifoldharmonics_build}/env.sh" ]; then
  . "${_manifoldharmonics_build}/env.sh"
else
  echo "scripts/env.sh: ${_manifoldharmonics_build}/env.sh not found; configure the build first" >&2
fi
unset _manifoldharmonics_build
