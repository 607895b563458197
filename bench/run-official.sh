#!/usr/bin/env bash
# Throughput table (Msamples/s, Mrays/s) for the official coursework scenes
# at 800x800 and 16 spp. Builds first; needs ../shared beside the checkout.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
shared=${SHARED_DIR:-$root/../shared}
bash "$root/scripts/build.sh"
mapfile -t scenes < <(find "$shared/scene-format/official" -name '*.json' | sort)
"$root/build/rt-bench" --width 800 --height 800 --spp 16 "${scenes[@]}" "$root/scenes/default.json" "$@"
