#!/usr/bin/env bash
# Installs the build into a scratch prefix, builds the example plugin from outside against it (as
# written, and with another plugin ABI number), then runs check_plugins.py on the installed library.
# Usage: check_plugins.sh BUILD SOURCE SCRATCH PYTHON BACKEND
set -euo pipefail
build="$1"; source="$2"; scratch="$3"; python="$4"; backend="$5"
rm -rf "$scratch"
cmake --install "$build" --prefix "$scratch/prefix" > /dev/null
configure() {  # configure NAME EXTRA-CMAKE-ARGS...
    local name="$1"; shift
    cmake -S "$source/examples/plugins" -B "$scratch/$name" -DCMAKE_PREFIX_PATH="$scratch/prefix" "$@" > "$scratch/$name.log" 2>&1 \
        || { cat "$scratch/$name.log"; exit 1; }
    cmake --build "$scratch/$name" >> "$scratch/$name.log" 2>&1 || { cat "$scratch/$name.log"; exit 1; }
}
configure plugin
# The same plugin, claiming another plugin ABI: the library must refuse it.
configure wrong_abi -DCMAKE_CXX_FLAGS=-DSTRUCTMD_PLUGIN_ABI_VERSION=999 \
                    -DCMAKE_CUDA_FLAGS=-DSTRUCTMD_PLUGIN_ABI_VERSION=999
args=()
if [ "$backend" = cuda ]; then
    # The plugin without its CUDA factories: a CUDA handle must refuse its component by name.
    configure cpu_only -DCMAKE_CUDA_FLAGS=-DSTRUCTMD_PLUGIN_NO_CUDA
    args=(--cpu-only "$scratch/cpu_only/yukawa.so")
fi
library=$(find "$scratch/prefix" -name 'libstructmd.so' | head -n 1)
STRUCTMD_LIBRARY="$library" PYTHONPATH="$source/bindings/python${PYTHONPATH:+:$PYTHONPATH}" \
    "$python" "$source/tests/plugins/check_plugins.py" --backend "$backend" \
    --plugin "$scratch/plugin/yukawa.so" --wrong-abi "$scratch/wrong_abi/yukawa.so" \
    --not-plugin "$library" --input "$source/examples/plugins/yukawa.json" "${args[@]}"
