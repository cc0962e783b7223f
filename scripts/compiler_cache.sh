# Sourced by the build scripts: `launcher` holds CMake's arguments for ccache where it is installed
# (scripts/install-deps.sh installs it), so that a second build of the same sources is a look-up,
# with paths hashed relative to the repository so that a clone elsewhere hits the same entries.
launcher=()
if command -v ccache > /dev/null; then
  launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_CUDA_COMPILER_LAUNCHER=ccache)
  CCACHE_BASEDIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
  export CCACHE_BASEDIR
fi
