#!/usr/bin/env bash
# Compiles the CUDA engines in single precision in build-cuda-check/ (the engines' library only: no
# examples or MPI, and of the tests only the check that the runtime kernels' headers compile under
# NVRTC), where nvcc is installed: device code that does not compile fails here, on a machine
# without a GPU. The suite does not run it (scripts/test.sh says why).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/compiler_cache.sh
cmake -S . -B build-cuda-check -DCMAKE_BUILD_TYPE=Release -DSTRUCTMD_CUDA=ON -DSTRUCTMD_PRECISIONS=single \
  -DSTRUCTMD_MPI=OFF -DSTRUCTMD_TESTS=ON -DSTRUCTMD_EXAMPLES=OFF "${launcher[@]}" > /dev/null
start=$SECONDS
cmake --build build-cuda-check -j"$(nproc)" --target structmd_engines test_runtime_headers > build-cuda-check/build.log 2>&1 \
  || { tail -50 build-cuda-check/build.log; echo "build_cuda_check: the CUDA engines do not compile" >&2; exit 1; }
echo "build_cuda_check: the CUDA engines (single precision) compile ($((SECONDS - start)) s)"
# NVRTC compiles for a virtual architecture without a GPU: a header that nvcc takes but kernels
# compiled at run time cannot include fails here too.
build-cuda-check/tests/runtime_kernels/test_runtime_headers
