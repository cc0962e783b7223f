#!/usr/bin/env bash
# Installs the build into a scratch prefix, then builds a consumer through find_package(structmd)
# and through pkg-config, and runs both against the installed library.
set -euo pipefail
build="$1"; source="$2"; scratch="$3"
rm -rf "$scratch"
cmake --install "$build" --prefix "$scratch/prefix" > /dev/null
cmake -S "$source/consumer" -B "$scratch/consumer" -DCMAKE_PREFIX_PATH="$scratch/prefix" > /dev/null
cmake --build "$scratch/consumer" > /dev/null
pcdir=$(find "$scratch/prefix" -name structmd.pc -printf '%h\n')
libdir=$(dirname "$pcdir")
LD_LIBRARY_PATH="$libdir" "$scratch/consumer/consumer"
flags=$(PKG_CONFIG_PATH="$pcdir" pkg-config --cflags --libs structmd)
cc -o "$scratch/consumer_pc" "$source/consumer/consumer.c" $flags
LD_LIBRARY_PATH="$libdir" "$scratch/consumer_pc"
"$scratch/prefix/bin/structmd" --version
