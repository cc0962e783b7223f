#!/usr/bin/env bash
# Builds the CPU backend with ThreadSanitizer in build-tsan/ and runs the tests labelled "threads"
# (handles driven from several threads at once) under it. Exits non-zero when a test fails or
# ThreadSanitizer reports anything.
#
# The OpenMP runtime is not built with ThreadSanitizer, so it could neither be checked nor keep
# quiet: the tests give each handle one thread ("threads": 1), and OMP_NUM_THREADS=1 covers any
# handle that does not say.
# Usage: scripts/tsan.sh   (JOBS=N for another build parallelism, default 1)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build="$root/build-tsan"
jobs=${JOBS:-1}

sanitize="-fsanitize=thread -fno-omit-frame-pointer"
cmake -S "$root" -B "$build" -DSTRUCTMD_CUDA=OFF -DSTRUCTMD_EXAMPLES=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS="$sanitize" -DCMAKE_CXX_FLAGS="$sanitize" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=thread" -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=thread" > /dev/null

# Only the programs of the thread tests are built. ctest names a test's program only once it exists,
# so the programs are read from the add_test lines CMake generated; each is a target of this build.
targets=$(cd "$build" && ctest -L threads --show-only=json-v1 | python3 -c '
import glob, json, os, re, sys
names = {t["name"] for t in json.load(sys.stdin)["tests"]}
programs = set()
for testfile in glob.glob("**/CTestTestfile.cmake", recursive=True):
    for name, program in re.findall(r"add_test\(\[=\[(.*?)\]=\]\s+\"([^\"]+)\"", open(testfile).read()):
        if name in names:
            programs.add(os.path.basename(program))
print(" ".join(sorted(programs)))')
if [ -z "$targets" ]; then
  echo "tsan: no test carries the label threads" >&2
  exit 1
fi
# shellcheck disable=SC2086  # one word per target
cmake --build "$build" -j"$jobs" --target $targets

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMP_NUM_THREADS=1
export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:log_path=$work/tsan"
status=0
(cd "$build" && ctest -L threads --output-on-failure) || status=1
if compgen -G "$work/tsan*" > /dev/null; then
  echo "== ThreadSanitizer reports"
  cat "$work"/tsan*
  status=1
fi
[ "$status" -eq 0 ] && echo "tsan: no test failed and ThreadSanitizer reported nothing"
exit "$status"
