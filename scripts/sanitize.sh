#!/usr/bin/env bash
# Builds the CPU backend with AddressSanitizer and UndefinedBehaviorSanitizer in build-asan/ and runs
# the test suite (benchmarks excluded) under them. Exits non-zero when a test fails or a sanitizer
# reports anything; the reports are printed at the end.
#
# Two groups of tests, because of how the ASan runtime has to be loaded:
#  - our own executables (gtest, C and Fortran hosts) run as built, with leak detection on;
#  - tests run by an interpreter or a shell script (Python, the install check) load libstructmd.so
#    into programs built without ASan. They get the ASan runtime preloaded, with libstdc++ beside it
#    (else ASan's __cxa_throw interceptor finds no real __cxa_throw and aborts at the engine's first
#    exception), and no leak detection, since Python keeps memory at exit by design.
# Usage: scripts/sanitize.sh   (JOBS=N for another build and ctest parallelism, default 2)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build="$root/build-asan"
jobs=${JOBS:-2}

# -fno-omit-frame-pointer for Fortran too: ASan's fast unwinder stops at Fortran frames without it.
sanitize="-fsanitize=address,undefined -fno-omit-frame-pointer"
cmake -S "$root" -B "$build" -DSTRUCTMD_CUDA=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS="$sanitize" -DCMAKE_CXX_FLAGS="$sanitize" -DCMAKE_Fortran_FLAGS="$sanitize" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" > /dev/null
cmake --build "$build" -j"$jobs"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir "$work/reports"
# A Fortran main program's allocatable variables live until the program ends and gfortran never
# frees them; LSan sees them as leaked once the main program's frame is gone.
cat > "$work/lsan.supp" <<'EOF'
leak:^coupling$
leak:^fortran_binding$
EOF

# ASan writes each report to reports/asan.<pid>, also from subprocesses whose stderr a test hides.
# UBSan ignores log_path when linked with ASan (GCC 12): its reports go to stderr, which ctest keeps in
# LastTest.log, so pytest must let the C library's stderr through (--capture=sys, not fd).
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS="suppressions=$work/lsan.supp:print_suppressions=0"
asan_options="halt_on_error=1:log_path=$work/reports/asan"

# Tests whose program is not one this build made.
hosted=$(cd "$build" && ctest --show-only=json-v1 | python3 -c '
import json, os, re, sys
build = os.path.realpath(sys.argv[1])
names = [t["name"] for t in json.load(sys.stdin)["tests"]
         if not os.path.realpath(t["command"][0]).startswith(build + os.sep)]
print("^(" + "|".join(map(re.escape, names)) + ")$" if names else "")' "$build")

# The resident-memory bound of robustness.lifecycle_memory measures the process's own allocator; under
# ASan, freed blocks wait in its quarantine and its metadata grows, so here LeakSanitizer does that job.
allocator_bound='^robustness\.lifecycle_memory$'

status=0
cd "$build"
echo "== built executables, leak detection on"
ASAN_OPTIONS="$asan_options:detect_leaks=1" \
  ctest -LE benchmark -E "${hosted:+$hosted|}$allocator_bound" -j"$jobs" --output-on-failure || status=1
cp Testing/Temporary/LastTest.log "$work/built.log"
if [ -n "$hosted" ]; then
  echo "== interpreters and scripts, ASan preloaded, leak detection off"
  compiler=$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' CMakeCache.txt)
  LD_PRELOAD="$("$compiler" -print-file-name=libasan.so) $("$compiler" -print-file-name=libstdc++.so)" \
  ASAN_OPTIONS="$asan_options:detect_leaks=0" PYTEST_ADDOPTS=--capture=sys \
    ctest -LE benchmark -R "$hosted" -j"$jobs" --output-on-failure || status=1
  cp Testing/Temporary/LastTest.log "$work/hosted.log"
fi

if compgen -G "$work/reports/*" > /dev/null; then
  echo "== AddressSanitizer / LeakSanitizer reports"
  cat "$work"/reports/*
  status=1
fi
if grep -h -A16 "runtime error:" "$work"/*.log; then
  echo "== the UndefinedBehaviorSanitizer reports above"
  status=1
fi
[ "$status" -eq 0 ] && echo "sanitize: no test failed and no sanitizer reported"
exit "$status"
