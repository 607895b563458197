#!/usr/bin/env bash
# Two builds of the renderer on the same scenes, renders interleaved (A, B,
# A, B, ...) so that the machine's drift hits both alike; prints a table of
# each build's best and median render time and B's speed over A's.
#   bench/run-ab.sh [--rounds N] A/raytracer B/raytracer -- SCENE "ARGS" [SCENE "ARGS"]...
# e.g. comparing a commit with the working tree:
#   git worktree add /tmp/before HEAD~1 && cmake -S /tmp/before -B /tmp/before/build -G Ninja \
#     && cmake --build /tmp/before/build --target raytracer
#   bench/run-ab.sh /tmp/before/build/raytracer build/raytracer -- scenes/default.json "--spp 16"
# Each build renders with its own shaders (the path compiled into it). The
# first render of each pair is untimed: it pays for the driver's compile.
# Timings are the renderer's own ("rendered ... in S s"), without start-up.
set -euo pipefail
rounds=5
if [[ ${1:-} == --rounds ]]; then
  rounds=$2
  shift 2
fi
a=${1:?usage: run-ab.sh [--rounds N] A B -- SCENE ARGS...}
b=${2:?usage: run-ab.sh [--rounds N] A B -- SCENE ARGS...}
shift 2
[[ ${1:-} == -- ]] && shift
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

render_seconds() {  # BINARY SCENE ARGS
  # shellcheck disable=SC2086  # ARGS is a list of options
  "$1" "$2" "$out/image.png" $3 2>&1 | sed -n 's/^rendered .* in \([0-9.]*\) s .*/\1/p'
}

results=$out/results.txt
: >"$results"
while (($# >= 2)); do
  scene=$1 args=$2
  shift 2
  render_seconds "$a" "$scene" "$args" >/dev/null
  render_seconds "$b" "$scene" "$args" >/dev/null
  for _ in $(seq "$rounds"); do
    echo "$scene|$args|A|$(render_seconds "$a" "$scene" "$args")" >>"$results"
    echo "$scene|$args|B|$(render_seconds "$b" "$scene" "$args")" >>"$results"
  done
done

python3 - "$results" "$a" "$b" "$rounds" <<'EOF'
import collections, statistics, sys
path, a, b, rounds = sys.argv[1:]
times = collections.defaultdict(list)
order = []
for line in open(path):
    scene, args, build, seconds = line.rstrip("\n").split("|")
    if (scene, args) not in order:
        order.append((scene, args))
    times[(scene, args, build)].append(float(seconds))
print(f"A: {a}\nB: {b}\n{rounds} interleaved renders each; seconds of rendering\n")
print("| scene | options | A best | A median | B best | B median | B speed / A (medians) |")
print("|---|---|---|---|---|---|---|")
for scene, args in order:
    ta, tb = times[(scene, args, "A")], times[(scene, args, "B")]
    ma, mb = statistics.median(ta), statistics.median(tb)
    print(f"| {scene.split('/')[-1]} | `{args}` | {min(ta):.3f} | {ma:.3f} | {min(tb):.3f} "
          f"| {mb:.3f} | {ma / mb:.2f}x |")
EOF
