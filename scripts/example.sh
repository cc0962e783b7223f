#!/usr/bin/env bash
# Sets up, builds and runs the bundled LJ liquid (32,000 particles) through the launcher, on the
# GPU when one is usable, else on the CPU. Extra arguments go to the launcher (--backend cpu, ...).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
STRUCTMD_TARGETS=structmd_launcher bash scripts/build.sh
cd examples
../build/src/launcher/structmd run lj_liquid.json "$@"
