#!/usr/bin/env bash
# Acceleration structure table (bench/bench_bvh.cpp): generated meshes from
# 1k to 5M triangles and the Stanford bunny, plus the BVH on/off render-time
# ratio on the official coursework example. Builds first; needs ../shared
# beside the checkout (or SHARED_DIR). Extra arguments go to rt-bench-bvh
# (e.g. --sizes 1000 10000, or --plain for the plain reference kernel on the
# bunny).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
shared=$(cd "${SHARED_DIR:-$root/../shared}" && pwd)
bash "$root/scripts/build.sh"
"$root/build/rt-bench-bvh" \
  --bunny "$shared/assets/ply/stanford-bunny/bunny/reconstruction/bun_zipper.ply" \
  --on-off "$shared/scene-format/official/cg-path-of-light-2019/example.json" \
  "$shared/scene-format/official/cgr-2023-2024/scene.json" "$@"
