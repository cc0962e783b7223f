#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite (benchmarks excluded; GPU tests report themselves
# skipped where no GPU is usable).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
cd build
ctest --output-on-failure -LE benchmark -j"$(nproc)"
# The libFuzzer targets, FUZZ_SECONDS (default 60) each, once the suite has passed.
JOBS="$(nproc)" bash ../scripts/fuzz.sh
