#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz with clang (AddressSanitizer and UndefinedBehaviorSanitizer
# over the engine too, CPU backend only) in build-fuzz/, then runs each target for FUZZ_SECONDS
# (default 60) over its committed corpus, tests/fuzz/corpus/<target>/. Exits non-zero on any crash,
# sanitizer report, leak, timeout (a call running over 10 s) or memory blow-up.
#
# The input that failed is left in build-fuzz/artifacts/<target>/; reproduce it with
# `build-fuzz/<target> FILE`, shrink it with `build-fuzz/<target> -minimize_crash=1 -runs=10000 FILE`
# and commit it to tests/fuzz/findings/<target>/ while the bug is open, to the corpus once it is
# fixed (so every later run replays it). Inputs that found new coverage are kept in
# build-fuzz/corpus/<target>/, not in the committed corpus. libFuzzer's own output goes to
# build-fuzz/logs/<target>.log; a target prints one line, and the log's end when it fails.
# Usage: scripts/fuzz.sh   (FUZZ_SECONDS=N per target, JOBS=N build parallelism, default 1)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build="$root/build-fuzz"
seconds=${FUZZ_SECONDS:-60}
jobs=${JOBS:-1}
targets=(fuzz_load_string fuzz_api_sequence fuzz_expression fuzz_create_options)

if ! command -v clang++ > /dev/null; then
  echo "fuzz: clang++ not found (bash scripts/install-deps.sh installs it)" >&2
  exit 1
fi
source "$root/scripts/compiler_cache.sh"
CC=clang CXX=clang++ cmake -S "$root/tests/fuzz" -B "$build" -DSTRUCTMD_FUZZ=ON "${launcher[@]}" \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo > /dev/null
cmake --build "$build" -j"$jobs" --target "${targets[@]}"

export UBSAN_OPTIONS=print_stacktrace=1
export ASAN_OPTIONS=detect_leaks=1
status=0
for target in "${targets[@]}"; do
  found="$build/corpus/$target"
  artifacts="$build/artifacts/$target"
  log="$build/logs/$target.log"
  mkdir -p "$found" "$artifacts" "$build/logs"
  # The fuzzed inputs may write files (measures, trajectories, checkpoints): they land in a scratch
  # directory, not in the repository.
  scratch=$(mktemp -d)
  if (cd "$scratch" && "$build/$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
      -max_len=16384 -print_final_stats=1 -artifact_prefix="$artifacts/" \
      "$found" "$root/tests/fuzz/corpus/$target") > "$log" 2>&1; then
    runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || true)
    echo "fuzz: $target: ${runs:-?} inputs in ${seconds} s, no finding (log: $log)"
  else
    status=1
    echo "fuzz: $target FAILED; the end of $log:" >&2
    tail -n 40 "$log" >&2
  fi
  rm -rf "$scratch"
done
if [ "$status" -ne 0 ]; then
  echo "fuzz: a target failed; its input is in $build/artifacts/" >&2
else
  echo "fuzz: no crash, sanitizer report or timeout"
fi
exit "$status"
