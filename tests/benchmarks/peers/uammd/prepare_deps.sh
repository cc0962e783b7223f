#!/usr/bin/env bash
# Fills the git-ignored .deps/ with what the UAMMD peer benchmark needs on the device, which has CUDA
# but no network, no LAPACKE and no CBLAS:
#   .deps/uammd   UAMMD's src/ at the snapshot's HEAD (git archive; the commit is in .deps/uammd/COMMIT)
#   .deps/lapack  Debian's reference LAPACKE, LAPACK, BLAS (with CBLAS) and the gfortran runtime they
#                 need: headers in include/, shared libraries in lib/ (UAMMD's Lanczos, used by PSE's
#                 near field, Lanczos and DPStokes, calls LAPACKE_?steqr and cblas_*; DPStokes also
#                 ?getrf/?getri). Their newest glibc symbol is GLIBC_2.34.
# Run here (it needs apt-get and the snapshot), from anywhere:
#   tests/benchmarks/peers/uammd/prepare_deps.sh [UAMMD_GIT_DIR]
set -euo pipefail
repo_root=$(git -C "$(dirname "$0")" rev-parse --show-toplevel)
uammd_git=${1:-/work/.mirror/RaulPPelaez+UAMMD/repo}
deps=$repo_root/.deps

rm -rf "$deps/uammd" "$deps/lapack"
mkdir -p "$deps/uammd" "$deps/lapack/include" "$deps/lapack/lib"
git -C "$uammd_git" archive HEAD src | tar -x -C "$deps/uammd"
git -C "$uammd_git" rev-parse HEAD > "$deps/uammd/COMMIT"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
packages=(liblapacke liblapacke-dev libtmglib3 liblapack3 libblas3 libblas-dev libgfortran5 libquadmath0)
(cd "$work" && apt-get download "${packages[@]}" 2>/dev/null)
for deb in "$work"/*.deb; do dpkg -x "$deb" "$work/root"; done
multiarch=$work/root/usr/lib/x86_64-linux-gnu
cp "$work"/root/usr/include/lapack*.h "$deps/lapack/include/"
# Debian chooses cblas.h through its alternatives; the reference BLAS's header is cblas-netlib.h.
cp "$work/root/usr/include/x86_64-linux-gnu/cblas-netlib.h" "$deps/lapack/include/cblas.h"
cp "$work/root/usr/include/x86_64-linux-gnu/cblas_mangling.h" "$deps/lapack/include/"
# Plain files under their sonames (links may not travel), found at run time through the rpath.
cp "$multiarch/liblapacke.so.3.11.0" "$deps/lapack/lib/liblapacke.so.3"
cp "$multiarch/libtmglib.so.3.11.0" "$deps/lapack/lib/libtmglib.so.3"
cp "$multiarch/lapack/liblapack.so.3.11.0" "$deps/lapack/lib/liblapack.so.3"
cp "$multiarch/blas/libblas.so.3.11.0" "$deps/lapack/lib/libblas.so.3"
cp "$multiarch/libgfortran.so.5.0.0" "$deps/lapack/lib/libgfortran.so.5"
cp "$multiarch/libquadmath.so.0.0.0" "$deps/lapack/lib/libquadmath.so.0"
(cd "$work" && ls -- *.deb) > "$deps/lapack/PACKAGES"
du -sh "$deps/uammd" "$deps/lapack"
