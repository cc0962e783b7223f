#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite (benchmarks excluded; GPU tests report themselves
# skipped where no GPU is usable).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
cd build
ctest --output-on-failure -LE benchmark -j"$(nproc)" 2>&1 | tee ctest.log
# The libFuzzer targets, FUZZ_SECONDS (default 60) each, once the suite has passed (pipefail stops
# here otherwise, with the summary last).
JOBS="$(nproc)" bash ../scripts/fuzz.sh
# The suite's summary last, where a reader of the log looks first.
sed -n '/tests passed/,$p' ctest.log
