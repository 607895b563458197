#!/usr/bin/env bash
# Throughput table (Msamples/s, Mrays/s) for the official coursework scenes,
# the default scene and the Stanford bunny, at 800x800 and 16 spp. Builds
# first; needs ../shared beside the checkout (or SHARED_DIR).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
shared=$(cd "${SHARED_DIR:-$root/../shared}" && pwd)
bash "$root/scripts/build.sh"
mkdir -p "$root/build/bench-scenes"
bunny="$root/build/bench-scenes/bunny.json"
sed "s|@BUNNY@|$shared/assets/ply/stanford-bunny/bunny/reconstruction/bun_zipper.ply|" \
  "$root/bench/bunny.json.in" >"$bunny"
mapfile -t scenes < <(find "$shared/scene-format/official" -name '*.json' | sort)
"$root/build/rt-bench" --width 800 --height 800 --spp 16 "${scenes[@]}" \
  "$root/scenes/default.json" "$bunny" "$@"
