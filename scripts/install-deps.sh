#!/usr/bin/env bash
# Installs what building and testing structmd needs on a Debian machine (idempotent). CUDA is used
# when nvcc is already installed; without it the build is CPU-only.
set -euo pipefail

packages=(cmake g++ gfortran make nlohmann-json3-dev librandom123-dev libcli11-dev libdlpack-dev libeigen3-dev googletest
          lammps python3 python3-pip curl
          doxygen  # the API reference rendered from include/structmd.h: test api_reference
          libopenmpi-dev openmpi-bin  # MPI (optional to the build): batches over ranks, tests/mpi
          clang libclang-rt-dev libomp-dev)  # clang, libFuzzer and clang's OpenMP: scripts/fuzz.sh
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
fi

# ase: the reference and the i-PI server of tests/python/test_ase.py and test_ipi.py.
if ! python3 -c "import numpy, cffi, pytest, ase" >/dev/null 2>&1; then
  python3 -m pip install -q numpy cffi pytest ase 2>/dev/null \
    || python3 -m pip install -q --break-system-packages numpy cffi pytest ase
fi

# pocketfft (the CPU backend's FFT, header only) into .deps/include, the git-ignored folder the build
# searches first, so that it travels with a copy of the working tree to machines without Debian's
# package. Debian 12 has no libpocketfft-dev, and only Debian and PyPI are reachable from CI, so where
# the package is missing the header comes from SciPy's source distribution on PyPI, which vendors it
# (BSD licence), at a fixed version and checked against its SHA-256.
deps_include="$(cd "$(dirname "$0")/.." && pwd)/.deps/include"
pocketfft_sha256=50f4ddbe60432325f560c706b6f1c49f9e0949fc7f20ae6499f2299e37d9790c
if [ ! -f "$deps_include/pocketfft_hdronly.h" ]; then
  mkdir -p "$deps_include"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  if DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq libpocketfft-dev >/dev/null 2>&1 \
      && [ -f /usr/include/pocketfft_hdronly.h ]; then
    cp /usr/include/pocketfft_hdronly.h "$deps_include/"
  else
    sdist=$(curl -fsSL https://pypi.org/simple/scipy/ | grep -oE 'https://files.pythonhosted.org/[^"#]*/scipy-1\.14\.1\.tar\.gz' | head -1)
    curl -fsSL "$sdist" | tar xzf - -O scipy-1.14.1/scipy/_lib/pocketfft/pocketfft_hdronly.h > "$deps_include/pocketfft_hdronly.h.part"
    echo "$pocketfft_sha256  $deps_include/pocketfft_hdronly.h.part" | sha256sum -c --quiet
    mv "$deps_include/pocketfft_hdronly.h.part" "$deps_include/pocketfft_hdronly.h"
  fi
fi

# Eigen (the CPU backend's Cholesky factorisation, the Lanczos solver's small eigenproblems; header
# only) into .deps/include/eigen3 for the same reason: the GPU machine has no libeigen3-dev.
if [ ! -f "$deps_include/eigen3/Eigen/Cholesky" ]; then
  mkdir -p "$deps_include/eigen3"
  cp -r /usr/include/eigen3/Eigen "$deps_include/eigen3/"
fi
