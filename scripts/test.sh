#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite (benchmarks excluded; GPU tests report themselves
# skipped where no GPU is usable).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
# The CUDA backend is built where a GPU can run its tests. Without one, compiling it would be most
# of the build on two cores for tests that only report themselves skipped; STRUCTMD_CUDA=ON (or OFF)
# in the environment decides instead.
cuda=${STRUCTMD_CUDA:-}
if [ -z "$cuda" ]; then
  if nvidia-smi -L > /dev/null 2>&1; then cuda=AUTO; else cuda=OFF; fi
fi
# The whole configuration is named, since scripts/example.sh leaves a lean one in build/'s cache.
bash scripts/build.sh -DSTRUCTMD_CUDA="$cuda" -DSTRUCTMD_MPI=AUTO -DSTRUCTMD_PRECISIONS="single;mixed;double" \
  -DSTRUCTMD_TESTS=ON -DSTRUCTMD_EXAMPLES=ON
# Without a GPU the suite compiles no CUDA engine (a quarter of an hour on two cores, and CI has an
# hour): device code is built and tested in all three precisions on a GPU before it lands. NVRTC
# still checks the headers of runtime kernels (runtime_kernels.headers_compile);
# scripts/build_cuda_check.sh compiles the CUDA engines in single precision, and
# STRUCTMD_TEST_CUDA_WHEEL=1 runs python_cuda_wheel (double).
cd build
ctest --output-on-failure -LE benchmark -j"$(nproc)" 2>&1 | tee ctest.log
# The libFuzzer targets, FUZZ_SECONDS (here 30 by default: each replays its corpus first, and CI has
# an hour on two cores) each, once the suite has passed (pipefail stops here otherwise, with the
# summary last).
FUZZ_SECONDS="${FUZZ_SECONDS:-30}" JOBS="$(nproc)" bash ../scripts/fuzz.sh
# The suite's summary last, where a reader of the log looks first.
sed -n '/tests passed/,$p' ctest.log
