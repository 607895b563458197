#!/usr/bin/env bash
# Installs what is missing, configures and builds into build/.
#   build.sh [--target NAME]... [CMAKE ARGS]
# --target builds only NAME (and what it needs), e.g. raytracer; other
# arguments go to CMake (e.g. -DRT_WARNINGS_AS_ERRORS=ON). RT_SKIP_SETUP=1
# skips the package install (machines without a network).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
targets=()
while [[ ${1:-} == --target ]]; do
  targets+=(--target "$2")
  shift 2
done
[[ -n "${RT_SKIP_SETUP:-}" ]] || bash "$root/scripts/setup.sh"
cmake -S "$root" -B "$root/build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "$@" >/dev/null
cmake --build "$root/build" --parallel "${targets[@]}"
