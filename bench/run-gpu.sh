#!/usr/bin/env bash
# The GPU report: builds, lists the Vulkan devices, runs the test suite and
# the benchmark tables on the first discrete GPU (the device every command
# picks by default: discrete > integrated > CPU), and writes one Markdown
# report. Absolute speed is only honest from a GPU; on lavapipe this prints
# the same tables as the other bench scripts.
#   bench/run-gpu.sh [REPORT.md]        (default: build/gpu-report.md)
# RT_SKIP_SETUP=1 skips the package install (machines without a network).
# RT_PREBUILT=1 skips the build and uses build/ as it is (a GPU machine with
# neither the packages nor a network: build on Debian 12, copy build/ over).
# RT_CTEST_EXCLUDE is the regex of ctest entries left out (default: farm,
# which needs scripts/setup.sh --farm; add viewer where there is no Xvfb).
set -uo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
shared=$(cd "${SHARED_DIR:-$root/../shared}" 2>/dev/null && pwd || echo "")
report=${1:-$root/build/gpu-report.md}
if [[ -z "${RT_PREBUILT:-}" ]]; then
  bash "$root/scripts/build.sh" -DRT_BUILD_TESTS=ON || exit 1
fi
mkdir -p "$(dirname "$report")"
scenes=("$root/scenes/default.json")
if [[ -n "$shared" ]]; then
  mapfile -t official < <(find "$shared/scene-format/official" -name '*.json' | sort)
  common=$shared/bench/common-scene
  scenes+=("${official[@]}" "$common/common_pinhole.json" "$common/common_dof.json")
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
# common_scene SPP_PINHOLE SPP_DOF: the common scene as
# ../shared/bench/common-scene/run.sh renders it (640x480; the render time the
# renderer prints, first kernel compile included), as Msamples/s per variant.
common_scene() {
  local variant spp seconds images
  images=$(mktemp -d)
  for variant in pinhole dof; do
    spp=$1
    [[ $variant == dof ]] && spp=$2
    seconds=$("$root/build/raytracer" "$common/common_$variant.json" "$images/$variant.png" \
      --size 640x480 --spp "$spp" 2>&1 | sed -n 's/^rendered .* in \([0-9.]*\) s .*/\1/p')
    awk -v variant="$variant" -v spp="$spp" -v s="$seconds" 'BEGIN {
      if (s == "") { print variant, spp " spp: FAILED"; exit }
      printf "%s %d spp: %.3f s, %.2f Msamples/s\n", variant, spp, s, 640 * 480 * spp / s / 1e6 }'
  done
  rm -rf "$images"
}

# The speed figures first, the test suite last: where time runs short, the
# tables are what this report is for.
section "Vulkan devices" "$root/build/raytracer" --device list
# A GPU idles at a fraction of its clock and takes a while under load to
# raise it: timings taken cold read up to 4x slower (an H200's bunny walk:
# 489 cold, 1963 Mrays/s warm). Five seconds of rendering first.
section "Warm-up (5 s of rendering, not timed)" "$root/build/raytracer" --quiet --time 5 --spp 65536 \
  --size 1920x1080 "$root/scenes/default.json" "$(mktemp -d)/warm-up.png"
# A GPU renders the other tables' 800x800 at 16 spp in a few milliseconds,
# which times the dispatches rather than the rays: 1920x1080 at 256 spp
# there (13-700 ms a scene on an H200); where only CPU devices are listed
# (the default pick prefers any GPU), the small size.
read -r width height spp < <(if "$root/build/raytracer" --device list | grep -q -v '(CPU,'; then
  echo 1920 1080 256
else
  echo 800 800 16
fi)
section "Scenes: rt-bench, ${width}x$height, $spp spp (bvh and hardware)" \
  "$root/build/rt-bench" --width "$width" --height "$height" --spp "$spp" "${scenes[@]}"
if [[ -n "$shared" ]]; then
  section "The common scene at run.sh's settings (16 / 64 spp)" common_scene 16 64
  section "The common scene at 1024 / 4096 spp (kernel compile amortised)" common_scene 1024 4096
  section "Meshes: rt-bench-bvh (BVH build, primary and diffuse rays)" \
    "$root/build/rt-bench-bvh" --bunny "$bunny" --plain
fi
# adaptive_sampling WIDTH HEIGHT: bench/run-adaptive.sh's comparison by wall
# clock (on a GPU the CPU time is the host's alone), on the thin-lens study and
# the common scene, against uniform jittered and Sobol.
adaptive_sampling() {
  local out=$root/build/adaptive-gpu scene name
  mkdir -p "$out"
  local studied=("$root/scenes/study-thinlens.json")
  [[ -n "$shared" ]] && studied+=("$common/common_dof.json")
  for scene in "${studied[@]}"; do
    name=$(basename "$scene" .json)
    "$root/build/raytracer" converge "$scene" --size "${1}x$2" --samplers jittered,sobol,adaptive \
      --spp-list 2,3,4,6,8,11,16,23,32,45,64,91 --reference-spp 2048 --repeat 3 \
      --out "$out/$name" -q >/dev/null || return 1
  done
  python3 "$root/bench/adaptive_table.py" --clock wall "$out" "${studied[@]}"
}
# On lavapipe the small size of bench/run-adaptive.sh.
adaptive_size=(320 240)
[[ $width == 1920 ]] && adaptive_size=(1920 1080)
section "Adaptive sampling: time to RMSE (converge, wall clock, ${adaptive_size[0]}x${adaptive_size[1]})" \
  adaptive_sampling "${adaptive_size[@]}"
section "Adaptive sampling: the host's work per round (rt-bench-adaptive)" \
  "$root/build/rt-bench-adaptive"
section "Test suite (ctest)" bash -c "cd '$root/build' && ctest --output-on-failure --parallel $(nproc) --timeout 600 -E '${RT_CTEST_EXCLUDE:-farm}'"
echo "wrote $report"
