#!/usr/bin/env bash
# Configures, builds and runs the whole test suite (ctest).
# Usage: scripts/build-and-test.sh [--sanitize] [BUILD_DIR]
#   (default)   Release build in build/ (or BUILD_DIR).
#   --sanitize  AddressSanitizer + UndefinedBehaviorSanitizer build of every library, the `conicloc`
#               binary and every test, in build-asan/ (or BUILD_DIR); any finding fails the run.
#               Same as CONICLOC_SANITIZE=1. Benchmarks are not built (they are not run by ctest),
#               nor the sharded-sweep tests on Slurm and GNU parallel (the Release build runs them).
# A compiler launcher such as ccache is taken from the environment (CMAKE_CXX_COMPILER_LAUNCHER).
set -euo pipefail
cd "$(dirname "$0")/.."

sanitize=${CONICLOC_SANITIZE:-0}
if [ "${1:-}" = "--sanitize" ]; then
  sanitize=1
  shift
fi

jobs=$(nproc)
if [ "$sanitize" = 1 ]; then
  build=${1:-build-asan}
  # -O1 keeps the stack traces exact and the suite fast enough; the frame pointer makes the
  # traces cheap. UBSan findings abort instead of printing and carrying on. -g1 keeps what a
  # trace needs (function names, line tables) and drops types and locals: with full -g every
  # test binary carried ~100 MB of debug info, 8.8 GB in all, and CI's disk ran out.
  flags="-O1 -g1 -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCONICLOC_BUILD_TESTS=ON \
    -DCONICLOC_BUILD_BENCHMARKS=OFF -DCONICLOC_CLUSTER_TESTS=OFF \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$flags" \
    -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
    -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
  # Leaks count; the first error aborts the process, so a test can't pass with a finding in it.
  export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
  export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
else
  build=${1:-build}
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCONICLOC_BUILD_TESTS=ON >/dev/null
fi
cmake --build "$build" --parallel "$jobs"
ctest --test-dir "$build" --output-on-failure --parallel "$jobs"
