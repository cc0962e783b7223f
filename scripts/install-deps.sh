#!/usr/bin/env bash
# Installs what building and testing structmd needs on a Debian machine (idempotent). CUDA is used
# when nvcc is already installed; without it the build is CPU-only. With the argument "build", only
# what the library and the launcher need (scripts/example.sh): a first run should not wait for
# LAMMPS, clang or MPI, which only the tests use.
set -euo pipefail

build_packages=(cmake g++ make nlohmann-json3-dev librandom123-dev libcli11-dev libdlpack-dev libeigen3-dev ccache)
test_packages=(googletest gfortran lammps python3 python3-pip
               doxygen  # the API reference rendered from include/structmd.h: test api_reference
               locales  # localedef and de_DE's definition: robustness.locale makes a decimal-comma locale
               libopenmpi-dev openmpi-bin  # MPI (optional to the build): batches over ranks, tests/mpi
               clang libclang-rt-dev libomp-dev)  # clang, libFuzzer and clang's OpenMP: scripts/fuzz.sh
profile=${1:-test}
case "$profile" in
  build) packages=("${build_packages[@]}") ;;
  test) packages=("${build_packages[@]}" "${test_packages[@]}") ;;
  *) echo "install-deps: unknown profile '$profile' (build or test)" >&2; exit 2 ;;
esac
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

# ase: the reference and the i-PI server of tests/python/test_ase.py and test_ipi.py; MDAnalysis: the
# reader of the DCD and its PSF topology in test_write_step.py; mkdocs and its extensions: the
# documentation site (scripts/docs_site.py, test docs_site).
python_packages=(numpy cffi pytest ase MDAnalysis mypy mkdocs pymdown-extensions "mkdocstrings[python]" mdx-truly-sane-lists)
if [ "$profile" = test ] && ! python3 -c "import numpy, cffi, pytest, ase, MDAnalysis, mypy, mkdocs, pymdownx, mkdocstrings, mdx_truly_sane_lists" >/dev/null 2>&1; then
  python3 -m pip install -q "${python_packages[@]}" 2>/dev/null \
    || python3 -m pip install -q --break-system-packages "${python_packages[@]}"
fi

# pocketfft (the CPU backend's FFT, header only) into .deps/include, the git-ignored folder the build
# searches first, so that it travels with a copy of the working tree to machines without it.
# Debian 13 packages it as libpocketfft-dev; Debian 12 does not, but its gemmi-dev ships the same
# header-only C++ pocketfft (BSD licence) under gemmi/third_party. Both come through apt-get.
deps_include="$(cd "$(dirname "$0")/.." && pwd)/.deps/include"
if [ ! -f "$deps_include/pocketfft_hdronly.h" ]; then
  mkdir -p "$deps_include"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  for source in libpocketfft-dev:/usr/include/pocketfft_hdronly.h \
                gemmi-dev:/usr/include/gemmi/third_party/pocketfft_hdronly.h; do
    package=${source%%:*} header=${source#*:}
    if [ -f "$header" ] || DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "$package" >/dev/null 2>&1; then
      [ -f "$header" ] && cp "$header" "$deps_include/pocketfft_hdronly.h" && break
    fi
  done
  if [ ! -f "$deps_include/pocketfft_hdronly.h" ]; then
    echo "install-deps: no Debian package gave pocketfft_hdronly.h (libpocketfft-dev or gemmi-dev)" >&2
    exit 1
  fi
fi

# Eigen (the CPU backend's Cholesky factorisation, the Lanczos solver's small eigenproblems; header
# only) into .deps/include/eigen3 for the same reason: the GPU machine has no libeigen3-dev.
if [ ! -f "$deps_include/eigen3/Eigen/Cholesky" ]; then
  mkdir -p "$deps_include/eigen3"
  cp -r /usr/include/eigen3/Eigen "$deps_include/eigen3/"
fi
