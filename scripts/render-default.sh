#!/usr/bin/env bash
# Quick start 1: on a fresh Debian 12 machine, installs, builds the renderer
# (only what this command runs) and renders the default scene to
# out/default.png (arguments are passed to raytracer).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/scripts/build.sh" --target raytracer
mkdir -p "$root/out"
"$root/build/raytracer" "$root/scenes/default.json" "$root/out/default.png" "$@"
echo "wrote $root/out/default.png"
