#!/usr/bin/env bash
# Quick start 2: on a fresh Debian 12 machine, installs, builds (warnings are
# errors) and runs the whole test suite. ../shared beside the checkout is
# used when present; the tests that need it are skipped otherwise.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/scripts/build.sh" -DRT_WARNINGS_AS_ERRORS=ON -DRT_BUILD_TESTS=ON
cd "$root/build"
ctest --output-on-failure --parallel 2 --timeout 600
