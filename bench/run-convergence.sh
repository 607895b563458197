#!/usr/bin/env bash
# The speed/accuracy study (README "Speed vs accuracy"): `raytracer converge`
# on the thin-lens and the area-light study scenes, random vs jittered vs
# Sobol, 9 to 2048 samples per pixel over a region, against an 8x reference.
# Prints each study's slope and time-to-RMSE table and writes the CSVs and
# log-log plots to build/convergence/. A few minutes each on two cores.
# Extra arguments go to both runs (e.g. --max-spp 256 for a quick look).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/scripts/build.sh"
out="$root/build/convergence"
mkdir -p "$out"
study() {
  local name=$1 region=$2
  shift 2
  echo "=== $name (region $region)"
  "$root/build/raytracer" converge "$root/scenes/study-$name.json" --region "$region" \
    --max-spp 2048 --clock cpu --out "$out/converge-$name" -q "$@"
}
study thinlens 72,140,64,64 "$@"
study arealight 140,120,64,64 "$@"
