#!/usr/bin/env bash
# Builds uammd_hydrodynamics.cu against UAMMD's headers for sm_90, once per precision (UAMMD chooses
# it at compile time: -DDOUBLE_PRECISION):
#   tests/benchmarks/peers/uammd/build.sh [UAMMD_SOURCE_DIR] [OUTPUT_DIR]
# UAMMD_SOURCE_DIR holds UAMMD's src/ (default .deps/uammd, made by prepare_deps.sh); OUTPUT_DIR gets
# uammd_hydrodynamics_single and uammd_hydrodynamics_double (default .deps/uammd-build). LAPACKE and
# CBLAS come from .deps/lapack (prepare_deps.sh), found at run time through the binaries' rpath.
# NVCC and CUDA_ARCH (default sm_90) may be set in the environment.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
repo_root=$(git -C "$here" rev-parse --show-toplevel)
uammd=$(realpath "${1:-$repo_root/.deps/uammd}")
out=$(realpath -m "${2:-$repo_root/.deps/uammd-build}")
lapack=$(realpath "$repo_root/.deps/lapack")
nvcc=${NVCC:-nvcc}
arch=${CUDA_ARCH:-sm_90}
[ -f "$uammd/src/uammd.cuh" ] || { echo "no UAMMD source at $uammd (run prepare_deps.sh)" >&2; exit 1; }
[ -f "$lapack/include/lapacke.h" ] || { echo "no LAPACKE at $lapack (run prepare_deps.sh)" >&2; exit 1; }
mkdir -p "$out"

# UAMMD's headers are system headers here: their warnings are UAMMD's, not this program's.
flags=(-O3 -std=c++20 -arch="$arch" --expt-relaxed-constexpr --extended-lambda
       -isystem "$uammd/src" -isystem "$uammd/src/third_party" -isystem "$lapack/include"
       -DMAXLOGLEVEL=3 -Xcompiler=-Wall -Xcompiler=-Wextra)
# The reference LAPACK's libraries under their sonames; RPATH (not RUNPATH) so that liblapacke's own
# dependencies are found in the same folder too.
libs=(-lcufft -lcublas -lcusolver -lcurand
      -L"$lapack/lib" -Xlinker -l:liblapacke.so.3 -Xlinker -l:libblas.so.3
      -Xlinker -rpath-link="$lapack/lib" -Xlinker --disable-new-dtags -Xlinker -rpath="$lapack/lib")

"$nvcc" "${flags[@]}" "$here/uammd_hydrodynamics.cu" -o "$out/uammd_hydrodynamics_single" "${libs[@]}" &
"$nvcc" "${flags[@]}" -DDOUBLE_PRECISION "$here/uammd_hydrodynamics.cu" -o "$out/uammd_hydrodynamics_double" "${libs[@]}" &
status=0
wait %1 || status=1
wait %2 || status=1
exit $status
