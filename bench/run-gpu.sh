#!/usr/bin/env bash
# The GPU report: builds, lists the Vulkan devices, runs the test suite and
# the benchmark tables on the first discrete GPU (the device every command
# picks by default: discrete > integrated > CPU), and writes one Markdown
# report. Absolute speed is only honest from a GPU; on lavapipe this prints
# the same tables as the other bench scripts.
#   bench/run-gpu.sh [REPORT.md]        (default: build/gpu-report.md)
# RT_SKIP_SETUP=1 skips the package install (machines without a network).
set -uo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
shared=$(cd "${SHARED_DIR:-$root/../shared}" 2>/dev/null && pwd || echo "")
report=${1:-$root/build/gpu-report.md}
bash "$root/scripts/build.sh" -DRT_BUILD_TESTS=ON || exit 1
mkdir -p "$(dirname "$report")"
scenes=("$root/scenes/default.json")
if [[ -n "$shared" ]]; then
  mapfile -t official < <(find "$shared/scene-format/official" -name '*.json' | sort)
  scenes+=("${official[@]}" "$shared/bench/common-scene/common_pinhole.json")
  bunny=$shared/assets/ply/stanford-bunny/bunny/reconstruction/bun_zipper.ply
fi

# section TITLE COMMAND...: the command's output as a fenced block.
section() {
  local title=$1 start=$SECONDS
  shift
  {
    printf '\n## %s\n\n```\n' "$title"
    "$@" 2>&1
    printf '```\n(%d s)\n' $((SECONDS - start))
  } >>"$report"
}

{
  echo "# GPU report"
  echo
  echo "$(date -u +%FT%TZ), commit $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown), $(nproc) CPU threads"
} >"$report"
section "Vulkan devices" "$root/build/raytracer" --device list
section "Test suite (ctest)" bash -c "cd '$root/build' && ctest --output-on-failure --parallel $(nproc) --timeout 600"
section "Scenes: rt-bench, 800x800, 16 spp (bvh and hardware)" \
  "$root/build/rt-bench" --width 800 --height 800 --spp 16 "${scenes[@]}"
if [[ -n "$shared" ]]; then
  section "Meshes: rt-bench-bvh (BVH build, primary and diffuse rays)" \
    "$root/build/rt-bench-bvh" --bunny "$bunny" --plain
fi
echo "wrote $report"
