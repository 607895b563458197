#!/usr/bin/env bash
# Builds with AddressSanitizer + UndefinedBehaviorSanitizer into build-asan/
# and runs the test suite there. Leak checking is off: the Vulkan driver
# (lavapipe) keeps allocations alive until process exit by design.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/scripts/setup.sh"
cmake -S "$root" -B "$root/build-asan" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DRT_SANITIZE=address,undefined -DRT_WARNINGS_AS_ERRORS=ON >/dev/null
cmake --build "$root/build-asan" --parallel
cd "$root/build-asan"
ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --output-on-failure --parallel 2 --timeout 900 "$@"
