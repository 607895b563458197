#!/usr/bin/env bash
# Adaptive sampling against uniform sampling over whole images (README
# "Adaptive sampling"): `raytracer converge` with random, jittered, Sobol
# and adaptive on the two study scenes, the common benchmark scene (thin
# lens) and the glass-and-mirror default scene, at 320x240, 2 to 362 mean
# samples per pixel against a 2048-sample Sobol reference. Prints per scene
# the time (process CPU seconds: lavapipe's work, steady on a busy machine)
# to RMSE 0.01 and 0.003 and each series' RMSE at the time adaptive needed;
# writes CSVs and plots to build/adaptive/. Each point is rendered REPEAT
# times (default 3) and timed by the median: single renders of a few samples
# move by 20-40% between runs. Roughly 10-15 minutes a scene on two cores.
# Extra arguments go to every run.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
shared=$(cd "${SHARED_DIR:-$root/../shared}" && pwd)
bash "$root/scripts/build.sh" --target raytracer
out="$root/build/adaptive"
mkdir -p "$out"
scenes=(
  "$root/scenes/study-thinlens.json"
  "$root/scenes/study-arealight.json"
  "$shared/bench/common-scene/common_dof.json"
  "$root/scenes/default.json"
)
for scene in "${scenes[@]}"; do
  name=$(basename "$scene" .json)
  echo "=== $name"
  "$root/build/raytracer" converge "$scene" --size 320x240 --samplers random,jittered,sobol,adaptive \
    --spp-list 2,3,4,6,8,11,16,23,32,45,64,91,128,181,256,362 --reference-spp 2048 --clock cpu --repeat "${REPEAT:-3}" --out "$out/$name" -q "$@" >"$out/$name.txt"
  cat "$out/$name.txt"
done
python3 "$root/bench/adaptive_table.py" "$out" "${scenes[@]}"
