#!/usr/bin/env bash
# Compiles the CUDA engines in single precision in build-cuda-check/ (the engines' library only: no
# tests, examples or MPI), where nvcc is installed: device code that does not compile fails here, on
# a machine without a GPU. scripts/test.sh runs it when it builds without CUDA.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/compiler_cache.sh
cmake -S . -B build-cuda-check -DCMAKE_BUILD_TYPE=Release -DSTRUCTMD_CUDA=ON -DSTRUCTMD_PRECISIONS=single \
  -DSTRUCTMD_MPI=OFF -DSTRUCTMD_TESTS=OFF -DSTRUCTMD_EXAMPLES=OFF "${launcher[@]}" > /dev/null
start=$SECONDS
cmake --build build-cuda-check -j"$(nproc)" --target structmd_engines > build-cuda-check/build.log 2>&1 \
  || { tail -50 build-cuda-check/build.log; echo "build_cuda_check: the CUDA engines do not compile" >&2; exit 1; }
echo "build_cuda_check: the CUDA engines (single precision) compile ($((SECONDS - start)) s)"
