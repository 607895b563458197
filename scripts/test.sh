#!/usr/bin/env bash
# Quick start 2: on a fresh Debian 12 machine, installs, builds and runs the
# whole test suite in three stages, each timed:
#   1. build/ (gcc, warnings are errors) and its ctest suite;
#   2. build-asan/ (clang, AddressSanitizer + UndefinedBehaviorSanitizer,
#      scripts/test-sanitizers.sh) and the same ctest suite on it;
#   3. the loader fuzzers on that build (scripts/fuzz.sh), RT_FUZZ_SECONDS
#      each (default 60).
# ../shared beside the checkout is used when present; the tests that need it
# are skipped otherwise.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
timings=()

# stage NAME COMMAND...: runs and times one stage; the first failure ends the run.
stage() {
  local name=$1 start=$SECONDS
  shift
  echo "=== $name"
  "$@"
  timings+=("$(printf '%-36s %4d s' "$name" $((SECONDS - start)))")
}

gcc_ctest() {
  (cd "$root/build" && ctest --output-on-failure --parallel 2 --timeout 600)
}

stage "setup (packages, rtfarm's venv)" bash "$root/scripts/setup.sh" --farm
stage "build (gcc)" bash "$root/scripts/build.sh" -DRT_WARNINGS_AS_ERRORS=ON -DRT_BUILD_TESTS=ON
stage "ctest (gcc)" gcc_ctest
stage "build (clang, ASan+UBSan, fuzzers)" bash "$root/scripts/build-sanitized.sh"
stage "ctest (ASan+UBSan)" bash "$root/scripts/test-sanitizers.sh"
stage "fuzzing" bash "$root/scripts/fuzz.sh" "${RT_FUZZ_SECONDS:-60}"
printf '%s\n' "=== stage times" "${timings[@]}"
