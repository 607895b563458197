#!/usr/bin/env bash
# Runs the whole test suite on the AddressSanitizer + UndefinedBehaviorSanitizer
# build (build-asan/, clang; see scripts/build-sanitized.sh). Any report fails
# the test that triggered it. Leak checking is off: the Vulkan driver
# (lavapipe) keeps allocations alive until process exit by design. Extra
# arguments go to ctest (e.g. -R scene).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/scripts/build-sanitized.sh"
cd "$root/build-asan"
ASAN_OPTIONS=detect_leaks=0:abort_on_error=1:strict_string_checks=1 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --output-on-failure --parallel 2 --timeout 900 "$@"
