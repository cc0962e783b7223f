#!/usr/bin/env bash
# On the device: UAMMD's rows of the hydrodynamics benchmark, then structmd's rows for the same methods
# and sizes (tests/benchmarks/hydrodynamics_benchmark.py), then both side by side. Run from the repo
# root with .deps/uammd and .deps/lapack carried (and .deps/uammd-build, if built here):
#   tests/benchmarks/peers/uammd/run.sh [OUTPUT_DIR]
# Writes into OUTPUT_DIR (default $OUT): uammd_hydrodynamics.csv and .log, structmd_hydrodynamics.csv
# and .log, comparison.md. Environment: SECONDS_PER_ROW (0.5, as docs/benchmarks.md's runs),
# TOLERANCE (1e-3), PRECISION (single: the precision of the steps/s; errors are always in double),
# REFERENCE_MAX (10000), STRUCTMD (1: also run structmd's side; it needs `import structmd` to work,
# e.g. PYTHONPATH set to a CUDA build of the binding).
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
repo_root=$(git -C "$here" rev-parse --show-toplevel 2>/dev/null || (cd "$here/../../../.." && pwd))
out=${1:-${OUT:?give an output folder or set OUT}}
seconds=${SECONDS_PER_ROW:-0.5}
tolerance=${TOLERANCE:-1e-3}
precision=${PRECISION:-single}
reference_max=${REFERENCE_MAX:-10000}
build=$repo_root/.deps/uammd-build
mkdir -p "$out"
log=$out/uammd_hydrodynamics.log
csv=$out/uammd_hydrodynamics.csv

# Each method and its sizes: the script's own sizes up to 100,000 (the dense ones stop where a step
# takes a large part of a second).
methods=(cholesky lanczos pse fcm quasi2d dpstokes)
declare -A sizes=([cholesky]="1000 2000" [lanczos]="1000 4000 16000" [pse]="1000 10000 100000"
                  [fcm]="1000 10000 100000" [quasi2d]="1000 10000 100000" [dpstokes]="1000 10000 100000")

# Binaries built here and carried run if the device's system libraries load them; else build there.
export LD_LIBRARY_PATH=$repo_root/.deps/lapack/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
loads() { [ -x "$1" ] && { "$1" >/dev/null 2>&1; [ $? -ne 127 ]; }; }
if ! loads "$build/uammd_hydrodynamics_single" || ! loads "$build/uammd_hydrodynamics_double"; then
  echo "building UAMMD's side on the device" | tee -a "$log"
  start=$(date +%s)
  "$here/build.sh" "$repo_root/.deps/uammd" "$build" >>"$log" 2>&1 || { echo "build failed, see $log"; exit 1; }
  echo "built in $(( $(date +%s) - start )) s" | tee -a "$log"
fi
echo "UAMMD $(cat "$repo_root/.deps/uammd/COMMIT" 2>/dev/null)" >>"$log"

echo "method,n,backend,precision,tolerance,steps_per_second,error" >"$csv"
start=$(date +%s)
for method in "${methods[@]}"; do
  for n in ${sizes[$method]}; do
    echo "== $method $n" >>"$log"
    rate=$("$build/uammd_hydrodynamics_$precision" rate --method "$method" --n "$n" --tolerance "$tolerance" \
           --seconds "$seconds" 2>>"$log")
    error=""
    if [ "$method" = cholesky ] || [ "$method" = lanczos ] || [ "$n" -le "$reference_max" ]; then
      error=$("$build/uammd_hydrodynamics_double" error --method "$method" --n "$n" --tolerance "$tolerance" 2>>"$log")
    fi
    shown_tolerance=$tolerance
    [ "$method" = cholesky ] && shown_tolerance=""
    echo "$method,$n,uammd,$precision,$shown_tolerance,$rate,$error" | tee -a "$csv"
  done
done
echo "UAMMD's side took $(( $(date +%s) - start )) s" | tee -a "$log"

if [ "${STRUCTMD:-1}" = 1 ]; then
  if python3 -c "import structmd" 2>/dev/null; then
    start=$(date +%s)
    for method in "${methods[@]}"; do
      args=()
      for n in ${sizes[$method]}; do args+=(--n "$n"); done
      PYTHONUNBUFFERED=1 python3 "$repo_root/tests/benchmarks/hydrodynamics_benchmark.py" --backend cuda \
        --precision "$precision" --tolerance "$tolerance" --seconds "$seconds" --reference-max "$reference_max" \
        --method "$method" "${args[@]}" --csv "$out/structmd_$method.csv" 2>&1 | tee -a "$out/structmd_hydrodynamics.log"
    done
    # One CSV for structmd too (the script writes one per call).
    python3 - "$out" <<'PY'
import glob, sys
out = sys.argv[1]
parts = sorted(glob.glob(f"{out}/structmd_*.csv"))
parts = [p for p in parts if not p.endswith("structmd_hydrodynamics.csv")]
lines = []
for p in parts:
    rows = open(p).read().splitlines()
    lines += rows if not lines else rows[1:]
open(f"{out}/structmd_hydrodynamics.csv", "w").write("\n".join(lines) + "\n")
import os
for p in parts:
    os.remove(p)
PY
    echo "structmd's side took $(( $(date +%s) - start )) s" | tee -a "$out/structmd_hydrodynamics.log"
  else
    echo "structmd is not importable here (set PYTHONPATH to a CUDA build of the binding): its side is skipped" \
      | tee -a "$out/structmd_hydrodynamics.log"
  fi
fi
python3 "$here/compare.py" "$csv" "$out/structmd_hydrodynamics.csv" | tee "$out/comparison.md"
