#!/usr/bin/env bash
# What the render farm (farm/, rtfarm) asks of build/raytracer: tiles
# (--region) that merge into the whole image, merge writing a scene's own
# 8-bit conventions (--scene), and frames of a viewer camera path rendered
# headless (--camera-path, --frame, --frame-count) as the viewer shows them.
# Usage: split_test.sh RAYTRACER SCENES_DIR SCRATCH_DIR
set -u
RAYTRACER=$1
SCENE=$2/default.json
SCRATCH=$3
rm -rf "$SCRATCH"
mkdir -p "$SCRATCH"
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

render() { "$RAYTRACER" "$SCENE" "$@" --size 32x24 --spp 2 -q; }
# ppm_size FILE: the "WIDTH HEIGHT" of a binary PPM.
ppm_size() { head -c 20 "$1" | sed -n 2p; }

# --- tiles ----------------------------------------------------------------
render "$SCRATCH/whole.ppm" && render "$SCRATCH/whole.exr" || fail "whole render"
render "$SCRATCH/top.exr" --region 0,0,32,10 && render "$SCRATCH/bottom.exr" --region 0,10,32,14 &&
  "$RAYTRACER" merge "$SCRATCH/top.exr" "$SCRATCH/bottom.exr" "$SCRATCH/tiles.ppm" --scene "$SCENE" 2>/dev/null &&
  cmp -s "$SCRATCH/tiles.ppm" "$SCRATCH/whole.ppm" && pass || fail "two tiles merge into the whole image"
"$RAYTRACER" merge "$SCRATCH/top.exr" "$SCRATCH/top.exr" "$SCRATCH/half.exr" 2>/dev/null &&
  fail "merging tiles that leave pixels without samples must fail" || pass
expect_failure out "region outside the image" '^error: --region: region 30,0,8,8 does not fit in the 32x24 image$' \
  "$SCENE" "$SCRATCH/out.exr" --size 32x24 --region 30,0,8,8
expect_failure out "malformed region" '^error: --region 1,2: expected X,Y,WIDTH,HEIGHT' \
  "$SCENE" "$SCRATCH/out.exr" --region 1,2

# --- merge --scene: the scene's 8-bit conventions (family B truncates) -------
"$RAYTRACER" merge "$SCRATCH/whole.exr" "$SCRATCH/plain.ppm" 2>/dev/null &&
  ! cmp -s "$SCRATCH/plain.ppm" "$SCRATCH/whole.ppm" && pass ||
  fail "without --scene, merge rounds where the default scene's render truncates"
expect_failure out "merge --scene of a missing scene" 'nope\.json' \
  merge "$SCRATCH/whole.exr" "$SCRATCH/out.png" --scene "$SCRATCH/nope.json"

# --- camera-path frames -----------------------------------------------------
cat >"$SCRATCH/path.txt" <<EOF
orbit 20 0   # frame 0
wait 2       # frames 1 and 2 keep it
zoom 2       # frame 3
screenshot ignored.png
resize 40 20 # frame 5
EOF
[[ $("$RAYTRACER" --camera-path "$SCRATCH/path.txt" --frame-count) == 6 ]] && pass || fail "--frame-count"
for frame in 0 2 3 5; do
  render "$SCRATCH/frame$frame.ppm" --camera-path "$SCRATCH/path.txt" --frame $frame || fail "frame $frame"
done
! cmp -s "$SCRATCH/frame0.ppm" "$SCRATCH/whole.ppm" && pass || fail "orbit moves the camera of frame 0"
cmp -s "$SCRATCH/frame0.ppm" "$SCRATCH/frame2.ppm" && pass || fail "wait keeps the camera"
! cmp -s "$SCRATCH/frame2.ppm" "$SCRATCH/frame3.ppm" && pass || fail "zoom moves the camera"
[[ $(ppm_size "$SCRATCH/frame5.ppm") == "40 20" ]] && pass || fail "resize sets the frame size"
render "$SCRATCH/default-frame.ppm" --camera-path "$SCRATCH/path.txt" &&
  cmp -s "$SCRATCH/default-frame.ppm" "$SCRATCH/frame0.ppm" && pass || fail "--frame defaults to 0"
expect_failure out "frame past the end" "^error: --frame 6: .*path.txt has 6 frame\(s\), 0\.\.5$" \
  "$SCENE" "$SCRATCH/out.png" --camera-path "$SCRATCH/path.txt" --frame 6
expect_failure out "--frame without a path" '--frame requires --camera-path' \
  "$SCENE" "$SCRATCH/out.png" --frame 1
printf 'lens 0.1 2\nfocus 10 10\n' >"$SCRATCH/focus.txt"
expect_failure out "focus cannot be replayed" "focus.txt:2: 'focus' needs the viewer's surface picking" \
  "$SCENE" "$SCRATCH/out.png" --camera-path "$SCRATCH/focus.txt" --frame 1
printf 'orbit 1\n' >"$SCRATCH/broken.txt"
expect_failure out "broken camera path" "broken.txt:1: 'orbit' takes 2 argument\(s\), got 1" \
  --camera-path "$SCRATCH/broken.txt" --frame-count

# The viewer shows the same frame (under Xvfb, when installed): its screenshot
# after the path's moves equals the headless render of that frame, bit for bit.
if command -v xvfb-run >/dev/null; then
  printf 'orbit 30 10\nzoom 2\npan 15 -10\nwait 5\nscreenshot %s\n' "$SCRATCH/viewer.png" >"$SCRATCH/viewer.path"
  xvfb-run -a -s "-screen 0 1280x1024x24" "$RAYTRACER" view "$SCENE" --size 64x48 --max-spp 2 \
    --spp-per-frame 1 --frames 10 --no-overlay --no-watch --camera-path "$SCRATCH/viewer.path" \
    >"$SCRATCH/viewer.log" 2>&1 || fail "viewer run: $(tail -3 "$SCRATCH/viewer.log")"
  "$RAYTRACER" "$SCENE" "$SCRATCH/headless.png" --size 64x48 --spp 2 -q \
    --camera-path "$SCRATCH/viewer.path" --frame 7 &&
    cmp -s "$SCRATCH/viewer.png" "$SCRATCH/headless.png" && pass ||
    fail "frame 7 of the path differs from the viewer's screenshot of it"
else
  echo "SKIP: xvfb-run is not installed; the viewer comparison needs a display"
fi

finish "split"
