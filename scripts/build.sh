#!/usr/bin/env bash
# Configures and builds structmd in build/ (CUDA backend when nvcc is found). Extra arguments go to
# the configure step; STRUCTMD_TARGETS (space-separated) builds only those targets, e.g. the
# launcher alone for the example, which needs neither the tests nor the host examples.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/compiler_cache.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" "$@"
if [ -n "${STRUCTMD_TARGETS:-}" ]; then
  # shellcheck disable=SC2086 # the targets are words
  cmake --build build -j"$(nproc)" --target ${STRUCTMD_TARGETS}
else
  cmake --build build -j"$(nproc)"
fi
