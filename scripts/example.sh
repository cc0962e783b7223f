#!/usr/bin/env bash
# Sets up, builds and runs the bundled LJ liquid (32,000 particles) through the launcher, on the
# GPU when one is usable, else on the CPU. Extra arguments go to the launcher (--backend cpu, ...).
#
# It builds only what this run needs, so that a first result comes in minutes: the launcher alone,
# the CUDA engines only where a GPU can run them (or --backend cuda asks for them), the one precision
# the run uses and no MPI. The compiler's output goes to a log file; scripts/test.sh configures the
# full build again.
set -euo pipefail
cd "$(dirname "$0")/.."

precision=single
cuda=OFF
if nvidia-smi -L > /dev/null 2>&1; then cuda=AUTO; fi
arguments=("$@")
for ((i = 0; i < ${#arguments[@]}; i++)); do
  case "${arguments[i]}" in
    --precision) precision=${arguments[i + 1]:-$precision} ;;
    --precision=*) precision=${arguments[i]#--precision=} ;;
    --backend) if [ "${arguments[i + 1]:-}" = cuda ]; then cuda=ON; fi ;;
    --backend=cuda) cuda=ON ;;
  esac
done

bash scripts/install-deps.sh build
mkdir -p build
log=build/example-build.log
echo "Building the launcher (CUDA engines: ${cuda}, precision: ${precision}) with $(nproc) cores; the compiler's output goes to ${log}."
start=$SECONDS
if ! STRUCTMD_TARGETS=structmd_launcher bash scripts/build.sh -DSTRUCTMD_CUDA="$cuda" -DSTRUCTMD_MPI=OFF \
    -DSTRUCTMD_PRECISIONS="$precision" -DSTRUCTMD_TESTS=OFF -DSTRUCTMD_EXAMPLES=OFF > "$log" 2>&1; then
  tail -n 40 "$log"
  echo "The build failed; the whole output is in ${log}." >&2
  exit 1
fi
echo "Built in $((SECONDS - start)) s."
cd examples
../build/src/launcher/structmd run lj_liquid.json "$@"
