#!/usr/bin/env bash
# Fails when a C++ source or a header shared with the shaders is not as
# clang-format (Debian 12's, .clang-format) would write it: the test suite's
# `format` entry. The GLSL files (.comp, .glsl) are not checked: clang-format
# has no GLSL mode, and they follow their own line breaks.
#   scripts/check-format.sh          check
#   scripts/check-format.sh --fix    rewrite the files in place
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
mapfile -t files < <(find src tests bench shaders -type f \
  \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' \) | sort)
if [[ ${1:-} == --fix ]]; then
  clang-format -i "${files[@]}"
  exit 0
fi
clang-format --dry-run -Werror "${files[@]}"
echo "clang-format: ${#files[@]} files as formatted"
