#!/usr/bin/env bash
# Installs the build into a scratch prefix and builds the example plugins (examples/plugins) from
# outside against it, then checks them on the installed library: CHECK "potential" (the default)
# builds Yukawa also with another plugin ABI number and runs check_plugins.py; "transversers" runs
# check_transverser_plugins.py on the three transverser plugins.
# Usage: check_plugins.sh BUILD SOURCE SCRATCH PYTHON BACKEND [CHECK]
set -euo pipefail
build="$1"; source="$2"; scratch="$3"; python="$4"; backend="$5"; check="${6:-potential}"
rm -rf "$scratch"
cmake --install "$build" --prefix "$scratch/prefix" > /dev/null
# Builds TARGET of the example plugins ("all": every one) in parallel: with CUDA each is a long nvcc
# compile, and built one at a time, all four in each of three configurations, the CUDA variant took
# 468 s on an H200 (stop 51), the longest test of the GPU label. Host code unoptimised (-O0, several
# times faster to compile): these tests check how a plugin is built, loaded and refused, and its
# forces, not its speed (the benchmarks build theirs optimised).
configure() {  # configure NAME TARGET EXTRA-CMAKE-ARGS...
    local name="$1" target="$2"; shift 2
    cmake -S "$source/examples/plugins" -B "$scratch/$name" -DCMAKE_PREFIX_PATH="$scratch/prefix" \
        -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-O0 -DCMAKE_CUDA_FLAGS_DEBUG=-O0 "$@" > "$scratch/$name.log" 2>&1 \
        || { cat "$scratch/$name.log"; exit 1; }
    cmake --build "$scratch/$name" --parallel --target "$target" >> "$scratch/$name.log" 2>&1 \
        || { cat "$scratch/$name.log"; exit 1; }
}
configure plugin all
library=$(find "$scratch/prefix" -name 'libstructmd.so' | head -n 1)
export STRUCTMD_LIBRARY="$library" PYTHONPATH="$source/bindings/python:$source/tests/python${PYTHONPATH:+:$PYTHONPATH}"
if [ "$check" = transversers ]; then
    exec "$python" "$source/tests/plugins/check_transverser_plugins.py" --backend "$backend" \
        --plugins "$scratch/plugin/neighbour_count.so" "$scratch/plugin/local_density.so" \
                  "$scratch/plugin/lennard_jones_force.so"
fi
# The same plugin, claiming another plugin ABI: the library must refuse it.
configure wrong_abi yukawa -DCMAKE_CXX_FLAGS=-DSTRUCTMD_PLUGIN_ABI_VERSION=999 \
                    -DCMAKE_CUDA_FLAGS=-DSTRUCTMD_PLUGIN_ABI_VERSION=999
args=()
if [ "$backend" = cuda ]; then
    # The plugin without its CUDA factories: a CUDA handle must refuse its component by name.
    configure cpu_only yukawa -DCMAKE_CUDA_FLAGS=-DSTRUCTMD_PLUGIN_NO_CUDA
    args=(--cpu-only "$scratch/cpu_only/yukawa.so")
fi
"$python" "$source/tests/plugins/check_plugins.py" --backend "$backend" \
    --plugin "$scratch/plugin/yukawa.so" --wrong-abi "$scratch/wrong_abi/yukawa.so" \
    --not-plugin "$library" --input "$source/examples/plugins/yukawa.json" "${args[@]}"
