#!/usr/bin/env bash
# Configures and builds build-asan/: clang with AddressSanitizer and
# UndefinedBehaviorSanitizer on every target, plus the libFuzzer targets
# (tests/fuzz; the rest carries fuzzer coverage instrumentation). One build
# serves both scripts/test-sanitizers.sh and scripts/fuzz.sh. Warnings are
# errors here too. The benchmarks are left out: timings under ASan mean
# nothing, and the gcc build compiles them. Extra arguments go to CMake.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/scripts/setup.sh"
cmake -S "$root" -B "$root/build-asan" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
  -DRT_SANITIZE=address,undefined -DRT_BUILD_FUZZERS=ON -DRT_BUILD_TESTS=ON -DRT_BUILD_BENCH=OFF \
  -DRT_WARNINGS_AS_ERRORS=ON "$@" >/dev/null
cmake --build "$root/build-asan" --parallel
