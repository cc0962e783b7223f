#!/usr/bin/env bash
# Installs the build into a scratch prefix, then builds consumers through find_package(structmd) and
# through pkg-config (C, and Fortran when the build has the module: FORTRAN=ON) and runs each with
# LD_LIBRARY_PATH unset: they must find the installed library through their run paths.
# usage: check_install.sh BUILD_DIR SOURCE_DIR SCRATCH_DIR FORTRAN
set -euo pipefail
build="$1"; source="$2"; scratch="$3"; fortran="$4"
rm -rf "$scratch"
cmake --install "$build" --prefix "$scratch/prefix" > /dev/null
prefix=$(cd "$scratch/prefix" && pwd)

# Runs a consumer without LD_LIBRARY_PATH and checks that it loaded the installed library.
run_installed() {
  env -u LD_LIBRARY_PATH "$1"
  # ldd's output is kept before it is searched: grep -q stopping early would otherwise fail the pipe
  # under pipefail whenever ldd is still writing.
  local libraries
  libraries=$(env -u LD_LIBRARY_PATH ldd "$1")
  if ! grep -q "libstructmd.so.* => $prefix/" <<< "$libraries"; then
    echo "$1 does not load libstructmd from $prefix:" >&2
    echo "$libraries" >&2
    exit 1
  fi
}

cmake -S "$source/consumer" -B "$scratch/consumer" -DCMAKE_PREFIX_PATH="$prefix" \
      -DSTRUCTMD_CONSUMER_FORTRAN="$fortran" > /dev/null
cmake --build "$scratch/consumer" > /dev/null
run_installed "$scratch/consumer/consumer"

pcdir=$(find "$prefix" -name structmd.pc -printf '%h\n')
cc -o "$scratch/consumer_pc" "$source/consumer/consumer.c" $(PKG_CONFIG_PATH="$pcdir" pkg-config --cflags --libs structmd)
run_installed "$scratch/consumer_pc"

if [ "$fortran" = ON ]; then
  run_installed "$scratch/consumer/consumer_fortran"
  gfortran -o "$scratch/consumer_fortran_pc" "$source/consumer/consumer.f90" \
           $(PKG_CONFIG_PATH="$pcdir" pkg-config --cflags --libs structmd-fortran)
  run_installed "$scratch/consumer_fortran_pc"
fi
"$prefix/bin/structmd" --version
