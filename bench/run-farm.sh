#!/usr/bin/env bash
# Render farm table (farm/bench/farm_bench.py): the time per task rtfarm adds
# over plain raytracer runs of the same parts, and the speed-up from one to
# two workers on local Ray clusters of this machine. Builds and installs
# first. Extra arguments go to the benchmark (e.g. --repeats 1, --size 320x240).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/scripts/build.sh"
exec "$root/build/farm-venv/bin/python" "$root/farm/bench/farm_bench.py" "$@"
