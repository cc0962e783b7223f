#!/usr/bin/env bash
# Before and after in one GPU lease: the working tree against an earlier commit, both built on the
# device machine and their benchmarks alternated, so that a change's gain is not confused with the
# spread between leases (docs/benchmarks.md quotes such pairs). Run from the repository root:
#
#   tests/benchmarks/ab_trees.sh prepare REV [NAME=REV2 ...]
#                                                here: the tree at REV into .deps/ab/before, and each
#                                                NAME=REV2 into .deps/ab/NAME (further trees, each set
#                                                against before too: two candidates in one lease), the
#                                                headers the device lacks into .deps/include, wheels
#                                                into .whl
#   tests/benchmarks/ab_trees.sh build           device: every tree's library and LJ benchmark built under
#                                                /tmp/ab, the trees side by side; a call cut short by
#                                                its time limit goes on where it stopped. The trees
#                                                are copied there by a lease's first call only: to
#                                                build a tree edited since, rm -rf /tmp/ab first.
#                                                Only the working tree is built whole (for the
#                                                label); the others with the component groups the
#                                                benchmarks use and no CPU engines
#   tests/benchmarks/ab_trees.sh label           device: the rest of the working tree's targets (tests,
#                                                other benchmarks; a call cut short goes on), then
#                                                ctest -L gpu in its build
#   tests/benchmarks/ab_trees.sh round K OUT     device: every tree's benchmarks, before first on odd K
#                                                and last on even K
#   tests/benchmarks/ab_trees.sh profile OUT     device, after build: Nsight Compute's full report
#                                                (ncu --set full) of the working tree's list build
#                                                and pair kernel in the LJ liquid (AB_PROFILE_N,
#                                                default 1000188; single precision), without step
#                                                graphs so each kernel is seen: OUT/profile-*.csv;
#                                                AB_PROFILE_TREE names another tree (default after)
#
# The device calls carry .deps and .whl (the device tool's `carry`). Environment (optional):
#   AB_BACKEND      cuda (default) or cpu (a smoke run on a machine without a GPU)
#   AB_PRECISIONS   the precisions built and run (default "single mixed double"; the LJ liquid runs all
#                   but double, and DPStokes's error, against a double-precision run, needs double).
#                   The working tree is built in all three for the label, and with the CPU
#                   engines, which the other trees leave out (STRUCTMD_CPU_ENGINES=OFF)
#   AB_LJ_SIZES     default "4000 10976 62500 1000188 4000000"
#   AB_CHAINS_SIZE  default 1000000 (0: no chains)
#   AB_DPSTOKES     DPStokes sizes, default "1000 10000" ("": none)
#   AB_WHOLE_AFTER  0: the working tree built lean like the others (a lease too short for the label
#                   measures alone; label then refuses it)
#   AB_SECONDS      seconds a timed call of the LJ benchmark (default 0.3; DPStokes: AB_HYDRO_SECONDS, 0.5)
#
# Each round writes OUT/round-K-TREE.csv (structmd_lj_benchmark's rows, liquid and chains) and
# OUT/round-K-TREE-hydro.csv (hydrodynamics_benchmark.py's), TREE being before, after or a further
# tree's name, and prints each tree's ratio to before for every row.
set -euo pipefail
cd "$(dirname "$0")/../.."

backend=${AB_BACKEND:-cuda}
precisions=${AB_PRECISIONS:-single mixed double}
work=/tmp/ab  # the trees' sources and builds: $work/before and $work/after

# The carried wheels into /tmp/site, where python3 lacks what they hold (the device machine).
install_wheels() {
  PYTHONPATH=/tmp/site python3 -c "import cffi, ase" 2> /dev/null && return
  python3 -m pip install -q --no-index --no-deps --no-compile --no-cache-dir --upgrade --target /tmp/site .whl/*.whl
}

# The trees, one a line: before, after (the working tree), then the further ones prepare made. The
# device reads them from the carried .deps/ab, so here and there they are the same.
trees() {
  echo before
  echo after
  for dir in .deps/ab/*/; do
    [ -d "$dir" ] || continue
    name=$(basename "$dir")
    [ "$name" = before ] || echo "$name"
  done
}

case "${1:-}" in
  prepare)
    rev=${2:?prepare needs a commit}
    rm -rf .deps/ab && mkdir -p .deps/ab/before
    git archive "$rev" | tar -x -C .deps/ab/before
    for named in "${@:3}"; do
      name=${named%%=*}
      [[ "$named" == *=* && "$name" =~ ^[a-z][a-z0-9-]*$ && "$name" != before && "$name" != after ]] || {
        echo "prepare: a further tree is NAME=REV, NAME in lower case and neither before nor after (got $named)"
        exit 2
      }
      mkdir -p ".deps/ab/$name" && git archive "${named#*=}" | tar -x -C ".deps/ab/$name"
    done
    bash scripts/install-deps.sh build
    for header in Random123 CLI dlpack; do
      [ -d ".deps/include/$header" ] || cp -r "/usr/include/$header" .deps/include/
    done
    # cffi for the Python binding; ase for the GPU label's Python tests (numpy and scipy are there).
    python3 -m pip download -q --no-deps --only-binary=:all: --python-version 3.12 --implementation cp \
      --platform manylinux_2_28_x86_64 --platform manylinux_2_17_x86_64 --platform manylinux2014_x86_64 \
      -d .whl cffi==1.17.1 pycparser==2.22 ase==3.23.0
    echo "prepared: .deps/ab/before at $(git rev-parse --short "$rev")${3:+, further trees: ${*:3}}, wheels in .whl"
    ;;
  build)
    if [ ! -d "$work/after" ]; then
      for tree in $(trees); do
        mkdir -p "$work/$tree/.deps"
        if [ "$tree" = after ]; then
          tar --exclude=./.deps --exclude=./.whl --exclude='./build*' -cf - . | tar -xf - -C "$work/after"
        else
          cp -r ".deps/ab/$tree/." "$work/$tree/"
        fi
        cp -r .deps/include "$work/$tree/.deps/"
      done
    fi
    cuda=$([ "$backend" = cuda ] && echo ON || echo OFF)
    # The trees build side by side: each build's last few long units leave most cores idle, which
    # the other trees' units fill.
    build_tree() {
      local tree=$1 source_dir=$work/$1 start=$SECONDS
      # The working tree has every precision and the CPU engines, whatever AB_PRECISIONS says: the
      # GPU label's Python tests and the precision comparison run in double, and some tests set the
      # backends side by side. The other trees are only timed on the GPU, so they leave the CPU
      # engines out, and the force-field components the benchmarks do not use: the liquid's
      # LennardJonesType1, the chains' WCAType1, harmonic bonds and Kratky-Porod angles (a tree
      # older than STRUCTMD_CPU_ENGINES or STRUCTMD_COMPONENT_GROUPS ignores it).
      local built=${precisions// /;} cpu_engines=$([ "$cuda" = ON ] && echo OFF || echo ON)
      local groups="lennardJonesPairs;repulsivePairs;bondedTerms"
      [ "$tree" = after ] && [ "${AB_WHOLE_AFTER:-1}" = 1 ] && built="single;mixed;double" cpu_engines=ON groups=""
      cmake -S "$source_dir" -B "$source_dir/build" -DCMAKE_BUILD_TYPE=Release -DSTRUCTMD_CUDA="$cuda" \
        "-DSTRUCTMD_PRECISIONS=$built" -DSTRUCTMD_CPU_ENGINES="$cpu_engines" \
        ${groups:+"-DSTRUCTMD_COMPONENT_GROUPS=$groups"} > "$work/$tree-configure.log" 2>&1
      if cmake --build "$source_dir/build" -j"$(nproc)" --target structmd structmd_lj_benchmark \
        > "$work/$tree-build.log" 2>&1; then
        echo "$tree built in $((SECONDS - start)) s"
      else
        grep -m 20 -B 2 -A 8 "error" "$work/$tree-build.log"
        echo "$tree: build failed after $((SECONDS - start)) s ($work/$tree-build.log)"
        return 1
      fi
    }
    builds=()
    for tree in $(trees); do
      build_tree "$tree" &
      builds+=($!)
    done
    failed=0
    for pid in "${builds[@]}"; do wait "$pid" || failed=1; done
    exit $failed
    ;;
  label)
    # A lean working tree (AB_WHOLE_AFTER=0) lacks components and precisions its tests need.
    grep -q '^STRUCTMD_COMPONENT_GROUPS:STRING=.*externalTerms' "$work/after/build/CMakeCache.txt" || {
      echo "label: the working tree was built lean (AB_WHOLE_AFTER=0); rm -rf $work/after/build and build it whole first"
      exit 2
    }
    export PYTHONPATH=/tmp/site
    install_wheels
    start=$SECONDS
    cmake --build "$work/after/build" -j"$(nproc)" > "$work/after-build-all.log" 2>&1 || {
      grep -m 20 -B 2 -A 8 "error" "$work/after-build-all.log"
      exit 1
    }
    echo "after: the rest of its targets built in $((SECONDS - start)) s"
    cd "$work/after/build" && ctest -L gpu -j12 --output-on-failure
    ;;
  round)
    round=${2:?round needs its number} out=${3:?round needs an output folder}
    mkdir -p "$out"
    install_wheels
    order=$(trees | tr '\n' ' ')
    [ $((round % 2)) -eq 0 ] && order=$(trees | tac | tr '\n' ' ')
    precision_flags=()
    for p in $precisions; do [ "$p" = double ] || precision_flags+=(--precision "$p"); done
    size_flags=()
    for n in ${AB_LJ_SIZES:-4000 10976 62500 1000188 4000000}; do size_flags+=(--n "$n"); done
    dpstokes_flags=()
    for n in ${AB_DPSTOKES-1000 10000}; do dpstokes_flags+=(--n "$n"); done
    # DPStokes's error is measured against a double-precision run, where the trees have double.
    reference_max=0
    [[ " $precisions " == *" double "* ]] && reference_max=1000
    for tree in $order; do
      source_dir=$work/$tree
      bench="$source_dir/build/tests/benchmarks/structmd_lj_benchmark"
      common=(--backend "$backend" --seconds "${AB_SECONDS:-0.3}" --repeats 2)
      "$bench" "${common[@]}" "${precision_flags[@]}" "${size_flags[@]}" --csv "$work/lj.csv" > /dev/null
      cp "$work/lj.csv" "$out/round-$round-$tree.csv"
      if [ "${AB_CHAINS_SIZE:-1000000}" != 0 ]; then
        "$bench" "${common[@]}" --precision single --scene chains --n "${AB_CHAINS_SIZE:-1000000}" \
          --csv "$work/chains.csv" > /dev/null
        tail -n +2 "$work/chains.csv" >> "$out/round-$round-$tree.csv"
      fi
      # One benchmark script times both trees' libraries, each through its own binding.
      if [ ${#dpstokes_flags[@]} -gt 0 ]; then
        STRUCTMD_LIBRARY="$source_dir/build/src/libstructmd.so" \
          PYTHONPATH="$source_dir/bindings/python:/tmp/site" \
          python3 "$work/after/tests/benchmarks/hydrodynamics_benchmark.py" --backend "$backend" \
          --seconds "${AB_HYDRO_SECONDS:-0.5}" --method dpstokes "${dpstokes_flags[@]}" --reference-max "$reference_max" \
          --csv "$out/round-$round-$tree-hydro.csv" > /dev/null
      fi
    done
    python3 - "$out" "$round" $order <<'EOF'
import csv, sys
out, round_, trees = sys.argv[1], sys.argv[2], [t for t in sys.argv[3:] if t != "before"]
def rows(tree, suffix, key, rate):
    try:
        with open(f"{out}/round-{round_}-{tree}{suffix}.csv") as f:
            return {tuple(r[k] for k in key): float(r[rate]) for r in csv.DictReader(f) if r.get(rate)}
    except FileNotFoundError:
        return {}
for suffix, key, rate in (("", ("scene", "n", "precision"), "particle_steps_per_second"),
                          ("-hydro", ("method", "n", "precision"), "steps_per_second")):
    before = rows("before", suffix, key, rate)
    for tree in sorted(trees):
        after = rows(tree, suffix, key, rate)
        for k in before:
            if k in after:
                print(f"round {round_} {tree} {' '.join(k)}: {before[k]:.4g} -> {after[k]:.4g} "
                      f"({100 * (after[k] / before[k] - 1):+.1f}%)")
EOF
    ;;
  profile)
    out=${2:?profile needs an output folder}
    mkdir -p "$out"
    command -v ncu > /dev/null || { echo "profile: ncu (Nsight Compute) is not on PATH"; exit 1; }
    build=$work/${AB_PROFILE_TREE:-after}/build
    # The trees other than after were built without the launcher.
    [ -x "$build/src/launcher/structmd" ] ||
      cmake --build "$build" -j"$(nproc)" --target structmd_launcher > "$work/profile-build.log" 2>&1
    "$build/tests/benchmarks/structmd_lj_benchmark" --scene lj --n "${AB_PROFILE_N:-1000188}" \
      --write-input "$work/profile-lj.json" > /dev/null
    # Without step graphs the build's kernel runs every step and returns at once where no build is
    # due: 16 of its launches hold two or three builds. Two pair kernels are enough.
    for kernel in BuildLists:16 PairKernel:2; do
      name=${kernel%%:*}
      ncu --clock-control none --set full --kernel-name-base demangled --kernel-name "regex:$name" \
        --launch-skip 20 --launch-count "${kernel##*:}" --csv --page details \
        "$build/src/launcher/structmd" run "$work/profile-lj.json" --backend "$backend" --precision single \
        --steps 60 --quiet --no-step-graphs > "$out/profile-$name.csv" 2> "$out/profile-$name.log"
      echo "profile: $name, $(grep -c '"Duration"' "$out/profile-$name.csv") launches in $out/profile-$name.csv"
    done
    ;;
  *)
    sed -n '2,/^set -euo/p' "$0" | grep '^#'
    exit 2
    ;;
esac
