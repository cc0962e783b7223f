#!/usr/bin/env bash
# Runs structmd's LJ liquid benchmark and its three peers (OpenMM, gamdpy, JAX MD) at the same sizes on
# a GPU machine, and writes their CSVs into one directory. See README.md beside this file.
#
#   tests/benchmarks/peers/run_peers.sh OUT_DIR [N ...]          (default N: 10976 62500 1000188 4000000)
#
# Environment (all optional):
#   STRUCTMD_BUILD      structmd build directory (default: build); its
#                       tests/benchmarks/structmd_lj_benchmark (and structmd_accuracy_benchmark for the
#                       drift) are run if present, else a line in peers.log says so
#   PEERS               which to run, in this order (default: "structmd openmm gamdpy jaxmd")
#   SECONDS_PER_SIZE    timed seconds per size and configuration for the peers (default 2); structmd
#                       runs 4 calls of SECONDS_PER_SIZE/4 s each and reports their median
#   STRUCTMD_PRECISIONS default "single mixed"
#   STRUCTMD_BACKEND    default cuda (cpu: for a smoke test on a machine without a GPU)
#   OPENMM_PLATFORM     default CUDA (CPU or Reference: for a smoke test without a GPU)
#   OPENMM_PRECISIONS   default "single mixed" (CUDA platform property 'Precision')
#   OPENMM_VARIANTS     default "custom nonbonded"
#   JAXMD_PRECISIONS    default "single" ("double" turns on jax_enable_x64)
#   JAXMD_VARIANTS      default "shifted switched"
#   GAMDPY_VARIANTS     default "default" ("autotuned" runs sim.autotune(): minutes per size)
#   DRIFT_TAU           if set (e.g. 100), also the energy drift over that many tau at N = 10,976, after
#                       10 tau of equilibration, for every engine (structmd through
#                       structmd_accuracy_benchmark at dt 0.005, skin 0.3)
#   PEER_TIMEOUT        seconds one engine may take for one size (default 300); it is killed after that,
#                       the others go on
#   WHEELS, SITE        wheels to install (default: .whl of the repository) and where (default /tmp/site);
#                       skipped if WHEELS has no *.whl
#
# Sizes run smallest first, every engine at one size before the next size, so a call cut short still
# has whole rows for the small sizes. A failure of one engine (import, platform, a size) is logged and
# written as a `*-failed` row; the others still run. Exit status 0 unless OUT_DIR cannot be made.
#
# Output (at most 7 files, within the device tool's 8):
#   OUT_DIR/structmd.csv        structmd_lj_benchmark --csv rows (its own columns)
#   OUT_DIR/structmd_drift.csv  structmd_accuracy_benchmark --csv rows (only with DRIFT_TAU)
#   OUT_DIR/openmm.csv, gamdpy.csv, jaxmd.csv   the peers' CSV (columns: see lj_common.py)
#   OUT_DIR/summary.csv         all engines in the peers' columns (structmd's rows converted)
#   OUT_DIR/peers.log           everything the programs printed on stderr/stdout besides CSV, and why
#                               anything failed
set -u

if [ $# -lt 1 ]; then
    echo "usage: $0 OUT_DIR [N ...]" >&2
    exit 2
fi
out=$1
shift
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(10976 62500 1000188 4000000)

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/../../.." && pwd)
mkdir -p "$out" || exit 2
out=$(cd "$out" && pwd)
log=$out/peers.log
: >"$log"

build=${STRUCTMD_BUILD:-build}
case $build in /*) ;; *) build=$repo/$build ;; esac
peers=${PEERS:-structmd openmm gamdpy jaxmd}
seconds=${SECONDS_PER_SIZE:-2}
timeout_s=${PEER_TIMEOUT:-300}
backend=${STRUCTMD_BACKEND:-cuda}
py=${PYTHON:-python3}

say() { echo "$*" | tee -a "$log"; }
say "run_peers.sh $(date -u +%Y-%m-%dT%H:%M:%SZ) sizes: ${sizes[*]} peers: $peers seconds: $seconds"
command -v nvidia-smi >/dev/null && nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader >>"$log" 2>&1

# --- wheels -> $SITE, on PYTHONPATH ----------------------------------------------------------------------
wheels=${WHEELS:-$repo/.whl}
site=${SITE:-/tmp/site}
if compgen -G "$wheels/*.whl" >/dev/null; then
    say "installing $(ls "$wheels"/*.whl | wc -l) wheels from $wheels into $site"
    if "$py" -m pip install -q --no-index --no-deps --no-compile --no-cache-dir --upgrade --target "$site" \
        "$wheels"/*.whl >>"$log" 2>&1; then
        export PYTHONPATH=$site${PYTHONPATH:+:$PYTHONPATH}
    else
        say "wheel install FAILED (see above); the peers use whatever is installed"
    fi
elif [ -d "$site" ]; then
    export PYTHONPATH=$site${PYTHONPATH:+:$PYTHONPATH}
fi
# OpenMM's CUDA plugin looks for libnvrtc.so.13 / libcufft.so.12 next to its own wheel; lj_openmm.py
# preloads them, and its runs also get the main environment's nvidia-* wheel folders on LD_LIBRARY_PATH.
nvlibs=$("$py" - <<'EOF' 2>/dev/null
import glob, importlib.util, os
spec = importlib.util.find_spec("nvidia")
dirs = []
for root in (spec.submodule_search_locations if spec and spec.submodule_search_locations else []):
    dirs += glob.glob(os.path.join(root, "cu13", "lib")) + glob.glob(os.path.join(root, "*", "lib"))
print(":".join(sorted(set(dirs))))
EOF
)
openmm_ld=${nvlibs}${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}  # for the OpenMM runs only
export PYTHONUNBUFFERED=1 NUMBA_CUDA_LOW_OCCUPANCY_WARNINGS=0

# --- one engine, one invocation -------------------------------------------------------------------------
# run_py NAME CSV SCRIPT ARGS...: appends the script's CSV rows to CSV (header once), stderr to the log.
run_py() {
    local name=$1 csv=$2 script=$3
    shift 3
    local tmp=$out/.tmp.csv
    echo "=== $name: $script $*" >>"$log"
    local t0=$SECONDS
    local ld=${LD_LIBRARY_PATH:-}
    [ "$name" = openmm ] && ld=$openmm_ld
    LD_LIBRARY_PATH=$ld timeout --kill-after=20 "$timeout_s" "$py" "$here/$script" "$@" >"$tmp" 2>>"$log"
    local rc=$?
    if [ -s "$tmp" ]; then
        if [ -s "$csv" ]; then tail -n +2 "$tmp" >>"$csv"; else cat "$tmp" >>"$csv"; fi
    fi
    rm -f "$tmp"
    case $rc in
        0) say "$name: ok ($((SECONDS - t0)) s) $*" ;;
        124 | 137) say "$name: TIMED OUT after ${timeout_s} s: $*" ;;
        *) say "$name: exit $rc ($((SECONDS - t0)) s; see peers.log) $*" ;;
    esac
}

structmd_bin=$build/tests/benchmarks/structmd_lj_benchmark
structmd_acc=$build/tests/benchmarks/structmd_accuracy_benchmark
run_structmd() {
    local n=$1
    if [ ! -x "$structmd_bin" ]; then
        say "structmd: no $structmd_bin (set STRUCTMD_BUILD): skipped"
        return
    fi
    local precisions=() p
    for p in ${STRUCTMD_PRECISIONS:-single mixed}; do precisions+=(--precision "$p"); done
    local per_call
    per_call=$(awk -v s="$seconds" 'BEGIN { printf "%g", s / 4 }')
    local tmp=$out/.tmp_structmd.csv
    echo "=== structmd: --n $n --backend $backend ${precisions[*]} --seconds $per_call --repeats 4" >>"$log"
    local t0=$SECONDS
    timeout --kill-after=20 "$timeout_s" "$structmd_bin" --n "$n" --backend "$backend" "${precisions[@]}" \
        --seconds "$per_call" --repeats 4 --csv "$tmp" >>"$log" 2>&1
    local rc=$?
    if [ -s "$tmp" ]; then
        if [ -s "$out/structmd.csv" ]; then tail -n +2 "$tmp" >>"$out/structmd.csv"; else cat "$tmp" >"$out/structmd.csv"; fi
    fi
    rm -f "$tmp"
    say "structmd: exit $rc ($((SECONDS - t0)) s) --n $n"
}

list_args() {  # list_args FLAG "a b c" -> FLAG a FLAG b FLAG c
    local flag=$1 v
    for v in $2; do printf '%s\n%s\n' "$flag" "$v"; done
}

run_engine() {  # run_engine PEER [ARGS...] (ARGS: --n N or --drift TAU)
    local peer=$1
    shift
    local extra=()
    case $peer in
        openmm)
            mapfile -t extra < <(list_args --precision "${OPENMM_PRECISIONS:-single mixed}"; list_args --variant "${OPENMM_VARIANTS:-custom nonbonded}")
            run_py openmm "$out/openmm.csv" lj_openmm.py "$@" --seconds "$seconds" --platform "${OPENMM_PLATFORM:-CUDA}" "${extra[@]}" ;;
        gamdpy)
            mapfile -t extra < <(list_args --variant "${GAMDPY_VARIANTS:-default}")
            run_py gamdpy "$out/gamdpy.csv" lj_gamdpy.py "$@" --seconds "$seconds" "${extra[@]}" ;;
        jaxmd)
            mapfile -t extra < <(list_args --precision "${JAXMD_PRECISIONS:-single}"; list_args --variant "${JAXMD_VARIANTS:-shifted switched}")
            run_py jaxmd "$out/jaxmd.csv" lj_jaxmd.py "$@" --seconds "$seconds" "${extra[@]}" ;;
        structmd) ;;
        *) say "unknown peer $peer: skipped" ;;
    esac
}

for n in "${sizes[@]}"; do
    for peer in $peers; do
        if [ "$peer" = structmd ]; then run_structmd "$n"; else run_engine "$peer" --n "$n"; fi
    done
done

if [ -n "${DRIFT_TAU:-}" ]; then
    for peer in $peers; do
        if [ "$peer" = structmd ]; then
            if [ -x "$structmd_acc" ]; then
                steps=$(awk -v t="$DRIFT_TAU" 'BEGIN { printf "%d", t / 0.005 + 0.5 }')
                samples=$(awk -v t="$DRIFT_TAU" 'BEGIN { s = int(t / 0.5 + 0.5); if (s < 2) s = 2; print s }')
                precisions=()
                for p in ${STRUCTMD_PRECISIONS:-single mixed}; do precisions+=(--precision "$p"); done
                echo "=== structmd drift: $DRIFT_TAU tau" >>"$log"
                timeout --kill-after=20 "$timeout_s" "$structmd_acc" --n 10976 --backend "$backend" "${precisions[@]}" \
                    --dt 0.005 --skin 0.3 --steps "$steps" --samples "$samples" --equilibrate 10 \
                    --csv "$out/structmd_drift.csv" >>"$log" 2>&1
                say "structmd drift: exit $?"
            else
                say "structmd drift: no $structmd_acc: skipped"
            fi
        else
            run_engine "$peer" --drift "$DRIFT_TAU"
        fi
    done
fi

# --- one table in the peers' columns --------------------------------------------------------------------
"$py" - "$out" <<'EOF' 2>>"$log"
import csv, os, sys
out = sys.argv[1]
header = ("engine,variant,n,precision,steps,seconds,steps_per_s,particle_steps_per_s,"
          "mode,drift_tau,drift_per_particle_per_tau,relative_force_error").split(",")
rows = []
path = os.path.join(out, "structmd.csv")
if os.path.exists(path):
    for r in csv.DictReader(open(path)):
        sps = float(r["steps_per_second"])
        steps = int(r["steps_per_call"])
        rows.append(["structmd", r.get("pair", "builtin"), r["n"], r["precision"], steps, f"{steps / sps:.6f}",
                     r["steps_per_second"], r["particle_steps_per_second"], "throughput", "", "", ""])
path = os.path.join(out, "structmd_drift.csv")
if os.path.exists(path):
    for r in csv.DictReader(open(path)):
        steps = int(r["steps"])
        sps = float(r["steps_per_second"])
        tau = steps * float(r["dt"])
        rows.append(["structmd", f"builtin-skin{r['skin']}", r["n"], r["precision"], steps, f"{steps / sps:.6f}",
                     r["steps_per_second"], f"{sps * int(r['n']):.6g}", "drift", f"{tau:g}", r["energy_drift"],
                     r["relative_force_error"]])
for name in ("openmm", "gamdpy", "jaxmd"):
    path = os.path.join(out, name + ".csv")
    if os.path.exists(path):
        for r in csv.reader(open(path)):
            if r and r[0] != "engine":
                rows.append(r)
with open(os.path.join(out, "summary.csv"), "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(header)
    w.writerows(rows)
print(",".join(header))
for r in rows:
    print(",".join(str(x) for x in r))
EOF
exit 0
