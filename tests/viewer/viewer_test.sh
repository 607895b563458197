#!/usr/bin/env bash
# Tests of `raytracer view`: real windows under Xvfb (xvfb-run) on whatever
# Vulkan device is picked (lavapipe in CI), with the validation layer on.
# Usage: viewer_test.sh CASE RAYTRACER IMAGE_COMPARE SOURCE_DIR SCRATCH_DIR
#   cli              bad arguments and files fail with one line (no window needed)
#   offscreen-match  a scripted session's swapchain screenshot equals the offline render
#   orbit            orbiting through --camera-path changes the image and restarts
#                    accumulation; orbiting back gives the first image again
#   resize           the render follows the window size
#   hot-reload       shader edits reload (and broken shaders do not stop the viewer),
#                    scene edits reload (and broken scenes are kept out)
set -u
CASE=$1
RAYTRACER=$2
COMPARE=$3
SOURCE=$4
SCRATCH=$5
rm -rf "$SCRATCH"
mkdir -p "$SCRATCH"
SCENE_SOURCE="$SOURCE/tests/viewer/scene.json"
SIZE=160x120
SPP=4
failed=0

fail() {
  echo "FAIL: $*"
  failed=$((failed + 1))
}

needs_display() {
  if ! command -v xvfb-run >/dev/null; then
    echo "SKIP: xvfb-run is not installed (apt-get install xvfb); the viewer tests need a display"
    exit 0
  fi
}

# xvfb_run CMD...: runs a command on its own virtual screen.
xvfb_run() {
  xvfb-run -a -s "-screen 0 1280x1024x24" "$@"
}

# offline OUT [ARGS...]: the render command's image of the test scene.
offline() {
  local out=$1
  shift
  "$RAYTRACER" "$SCENE_SOURCE" "$out" --size $SIZE --spp $SPP -q "$@" || fail "offline render $out"
}

# compare NAME A B ARGS...: rt_image_compare with bounds; reports the numbers.
compare() {
  local name=$1 a=$2 b=$3
  shift 3
  local result
  result=$("$COMPARE" "$a" "$b" "$@" 2>&1)
  local status=$?
  echo "$name: $result"
  [[ $status -eq 0 ]] || fail "$name: $result (wanted $*)"
}

# wait_for FILE PATTERN COUNT SECONDS: until FILE has COUNT lines matching
# the extended regex PATTERN; fails after SECONDS.
wait_for() {
  local file=$1 pattern=$2 count=$3 seconds=$4
  local deadline=$((SECONDS + seconds))
  while ((SECONDS < deadline)); do
    if [[ $(grep -Ec -- "$pattern" "$file" 2>/dev/null) -ge $count ]]; then return 0; fi
    if [[ -n ${VIEWER_PID:-} ]] && ! kill -0 "$VIEWER_PID" 2>/dev/null; then
      fail "viewer exited while waiting for $count x '$pattern' in $(basename "$file")"
      return 1
    fi
    sleep 0.1
  done
  fail "timed out waiting for $count x '$pattern' in $(basename "$file")"
  return 1
}

case_cli() {
  local out
  out=$("$RAYTRACER" view 2>&1)
  [[ $? -eq 2 ]] || fail "no scene: expected exit status 2"
  out=$("$RAYTRACER" view "$SCRATCH/missing.json" 2>&1)
  [[ $? -eq 1 && $(echo "$out" | wc -l) -eq 1 && $out == *missing.json* ]] ||
    fail "missing scene: expected one error line naming the file, got: $out"
  printf 'orbit 10 0\nspin 3\n' >"$SCRATCH/bad.path"
  out=$("$RAYTRACER" view "$SCENE_SOURCE" --camera-path "$SCRATCH/bad.path" 2>&1)
  [[ $? -eq 1 && $out == *bad.path:2:*spin* ]] ||
    fail "bad camera path: expected 'bad.path:2: unknown step', got: $out"
  out=$("$RAYTRACER" view "$SCENE_SOURCE" --screenshot "$SCRATCH/shot.bmp" 2>&1)
  [[ $? -eq 1 && $out == *"must be a .png, .jpg or .ppm file"* ]] ||
    fail "bmp screenshot: expected an error, got: $out"
  out=$("$RAYTRACER" view "$SCENE_SOURCE" --size 0x10 2>&1)
  [[ $? -eq 1 && $out == *--size* ]] || fail "bad size: expected an error, got: $out"
}

case_offscreen_match() {
  needs_display
  offline "$SCRATCH/offline.png"
  xvfb_run "$RAYTRACER" view "$SCENE_SOURCE" --size $SIZE --max-spp $SPP --spp-per-frame 1 \
    --frames 6 --no-overlay --no-watch --validation --screenshot "$SCRATCH/window.png" \
    >"$SCRATCH/log" 2>"$SCRATCH/err"
  local status=$?
  [[ $status -eq 0 ]] || fail "viewer exit status $status: $(cat "$SCRATCH/err")"
  grep -q "^done: spp=$SPP " "$SCRATCH/log" || fail "no 'done: spp=$SPP' line in the log"
  compare "window vs offline" "$SCRATCH/window.png" "$SCRATCH/offline.png" --max-diff 0
  # The same frame as a JPEG screenshot: the format follows the extension.
  xvfb_run "$RAYTRACER" view "$SCENE_SOURCE" --size $SIZE --max-spp $SPP --spp-per-frame 1 \
    --frames 6 --no-overlay --no-watch --screenshot "$SCRATCH/window.jpg" >/dev/null 2>&1 ||
    fail "jpeg screenshot: viewer exit status $?"
  [[ $(head -c 3 "$SCRATCH/window.jpg" | od -An -tx1 | tr -d ' ') == ffd8ff ]] ||
    fail "jpeg screenshot: not a JPEG file"
  compare "jpeg window vs offline" "$SCRATCH/window.jpg" "$SCRATCH/offline.png" --min-psnr 30

  # A tone curve: the window's display pass applies it as the PNG writer does
  # (float rounding may move a byte by one); it changes the image.
  offline "$SCRATCH/offline-aces.png" --tone-curve aces --exposure 2
  xvfb_run "$RAYTRACER" view "$SCENE_SOURCE" --size $SIZE --max-spp $SPP --spp-per-frame 1 \
    --frames 6 --no-overlay --no-watch --validation --tone-curve aces --exposure 2 \
    --screenshot "$SCRATCH/window-aces.png" >"$SCRATCH/log-aces" 2>"$SCRATCH/err-aces" ||
    fail "viewer with --tone-curve aces: $(cat "$SCRATCH/err-aces")"
  compare "aces window vs offline" "$SCRATCH/window-aces.png" "$SCRATCH/offline-aces.png" \
    --max-diff 1
  offline "$SCRATCH/offline-exposed.png" --exposure 2
  compare "aces vs clamp" "$SCRATCH/offline-aces.png" "$SCRATCH/offline-exposed.png" --max-psnr 40

  # Adaptive sampling: the window's rounds (one a frame) decide as the render
  # command's do, so the two images are the same.
  "$RAYTRACER" "$SCENE_SOURCE" "$SCRATCH/offline-adaptive.png" --size $SIZE --spp 16 --adaptive -q ||
    fail "offline adaptive render"
  xvfb_run "$RAYTRACER" view "$SCENE_SOURCE" --size $SIZE --max-spp 16 --adaptive \
    --spp-per-frame 1 --frames 30 --no-overlay --no-watch --validation \
    --screenshot "$SCRATCH/window-adaptive.png" >"$SCRATCH/log-adaptive" 2>"$SCRATCH/err-adaptive"
  status=$?
  [[ $status -eq 0 ]] || fail "adaptive viewer exit status $status: $(cat "$SCRATCH/err-adaptive")"
  grep -Eq "^done: spp=[0-9]+\.[0-9]+ mean " "$SCRATCH/log-adaptive" ||
    fail "no 'done: spp=... mean' line in the adaptive viewer's log"
  compare "adaptive window vs offline" "$SCRATCH/window-adaptive.png" \
    "$SCRATCH/offline-adaptive.png" --max-diff 0

  # The same with the overlay on: the screenshot is the presented image, so
  # the overlay shows in it (and only covers part of it).
  xvfb_run "$RAYTRACER" view "$SCENE_SOURCE" --size 640x480 --max-spp 1 --spp-per-frame 1 \
    --frames 3 --no-watch --validation --screenshot "$SCRATCH/overlay.png" \
    >"$SCRATCH/log-overlay" 2>"$SCRATCH/err-overlay" || fail "viewer with overlay failed"
  "$RAYTRACER" "$SCENE_SOURCE" "$SCRATCH/offline-640.png" --size 640x480 --spp 1 -q
  compare "overlay vs offline" "$SCRATCH/overlay.png" "$SCRATCH/offline-640.png" --max-psnr 35
  # In a small window the panel collapses to its title bar: the image stays visible.
  xvfb_run "$RAYTRACER" view "$SCENE_SOURCE" --size 320x240 --max-spp 1 --spp-per-frame 1 \
    --frames 3 --no-watch --validation --screenshot "$SCRATCH/overlay-small.png" \
    >"$SCRATCH/log-overlay" 2>"$SCRATCH/err-overlay" || fail "viewer with overlay (small) failed"
  "$RAYTRACER" "$SCENE_SOURCE" "$SCRATCH/offline-320.png" --size 320x240 --spp 1 -q
  compare "small window: overlay covers" "$SCRATCH/overlay-small.png" "$SCRATCH/offline-320.png" \
    --max-differing 0.1

  # The light options: the window's area lights take the count (--light-samples) and the
  # replicas (--light-split) the render command's do, on the area-light study, and either
  # differs from the scene's own (another image where its coursework shading clamps each
  # hit's light, other shadow rays where the replicas keep it).
  local study="$SOURCE/scenes/study-arealight.json" option
  "$RAYTRACER" "$study" "$SCRATCH/study-1.png" --size $SIZE --spp $SPP -q || fail "study render"
  for option in --light-samples --light-split; do
    "$RAYTRACER" "$study" "$SCRATCH/study$option.png" --size $SIZE --spp $SPP "$option" 3 -q ||
      fail "study render with $option 3"
    xvfb_run "$RAYTRACER" view "$study" --size $SIZE --max-spp $SPP --spp-per-frame 1 --frames 6 \
      --no-overlay --no-watch --validation "$option" 3 --screenshot "$SCRATCH/window$option.png" \
      >"$SCRATCH/log$option" 2>"$SCRATCH/err$option" ||
      fail "viewer with $option: $(cat "$SCRATCH/err$option")"
    compare "$option 3: window vs offline" "$SCRATCH/window$option.png" \
      "$SCRATCH/study$option.png" --max-diff 0
    compare "$option 3 vs the scene's own" "$SCRATCH/study$option.png" "$SCRATCH/study-1.png" \
      --max-psnr 45
  done

  # A second scene with textures and thin features, when the shared data is there.
  local example="$SOURCE/../shared/scene-format/official/cg-path-of-light-2021-2023/examples/example.json"
  if [[ -f $example ]]; then
    "$RAYTRACER" "$example" "$SCRATCH/example-offline.png" --size 200x200 --spp 2 -q 2>/dev/null
    xvfb_run "$RAYTRACER" view "$example" --size 200x200 --max-spp 2 --spp-per-frame 1 --frames 3 \
      --no-overlay --no-watch --validation --screenshot "$SCRATCH/example-window.png" \
      >"$SCRATCH/log-example" 2>"$SCRATCH/err-example" || fail "viewer on example.json failed"
    compare "example.json window vs offline" "$SCRATCH/example-window.png" \
      "$SCRATCH/example-offline.png" --min-psnr 40 --max-diff 2
  fi
}

case_orbit() {
  needs_display
  offline "$SCRATCH/offline.png"
  cat >"$SCRATCH/orbit.path" <<EOF
# frames 1-4 accumulate $SPP spp, frame 6 is shown complete
wait 5
screenshot $SCRATCH/start.png
orbit 30 0
wait 5
screenshot $SCRATCH/orbited.png
orbit -30 0
wait 5
screenshot $SCRATCH/back.png
EOF
  xvfb_run "$RAYTRACER" view "$SCENE_SOURCE" --size $SIZE --max-spp $SPP --spp-per-frame 1 \
    --frames 20 --no-overlay --no-watch --validation --verbose \
    --camera-path "$SCRATCH/orbit.path" >"$SCRATCH/log" 2>"$SCRATCH/err"
  local status=$?
  [[ $status -eq 0 ]] || fail "viewer exit status $status: $(cat "$SCRATCH/err")"
  compare "start vs offline" "$SCRATCH/start.png" "$SCRATCH/offline.png" --min-psnr 40 --max-diff 2
  compare "orbited vs start" "$SCRATCH/orbited.png" "$SCRATCH/start.png" --max-psnr 30
  compare "back vs start" "$SCRATCH/back.png" "$SCRATCH/start.png" --min-psnr 40
  # Each orbit restarts accumulation: three complete accumulations, and a
  # frame at 1 spp right after a frame at the full count.
  [[ $(grep -c "^done: spp=$SPP " "$SCRATCH/log") -eq 3 ]] ||
    fail "expected 3 completed accumulations: $(grep '^done' "$SCRATCH/log")"
  grep '^frame ' "$SCRATCH/log" | grep -A1 "spp=$SPP/$SPP" | grep -q "spp=1/$SPP" ||
    fail "no restart to 1 spp after a full accumulation in the log"
}

case_resize() {
  needs_display
  "$RAYTRACER" "$SCENE_SOURCE" "$SCRATCH/offline-200.png" --size 200x150 --spp $SPP -q ||
    fail "offline render"
  cat >"$SCRATCH/resize.path" <<EOF
wait 3
resize 200 150
wait 8
screenshot $SCRATCH/resized.png
EOF
  xvfb_run "$RAYTRACER" view "$SCENE_SOURCE" --size $SIZE --max-spp $SPP --spp-per-frame 1 \
    --frames 14 --no-overlay --no-watch --validation --camera-path "$SCRATCH/resize.path" \
    >"$SCRATCH/log" 2>"$SCRATCH/err"
  local status=$?
  [[ $status -eq 0 ]] || fail "viewer exit status $status: $(cat "$SCRATCH/err")"
  grep -q "^resize: rendering at 200x150" "$SCRATCH/log" || fail "no resize line in the log"
  compare "resized window vs offline" "$SCRATCH/resized.png" "$SCRATCH/offline-200.png" \
    --min-psnr 40 --max-diff 2
}

# edit FILE SED_EXPRESSION: an editor-style save (write a copy, rename it over).
edit() {
  sed -e "$2" "$1" >"$1.tmp" && mv "$1.tmp" "$1"
}

case_hot_reload() {
  needs_display
  local shaders="$SCRATCH/shaders" edited="$SCRATCH/shaders-edited" scene="$SCRATCH/scene.json"
  cp -r "$SOURCE/shaders" "$shaders"
  cp -r "$SOURCE/shaders" "$edited"
  cp "$SCENE_SOURCE" "$scene"
  # A visible edit of the render kernel: swap red and blue of every sample.
  local swap='s/finiteOrZero(radiance)/finiteOrZero(radiance).bgr/'
  grep -q 'finiteOrZero(radiance)' "$shaders/trace.comp" ||
    { fail "trace.comp no longer has 'finiteOrZero(radiance)'; update the edit in this test"; return; }
  edit "$edited/trace.comp" "$swap"
  local changed_scene="$SCRATCH/scene-changed.json"
  sed -e 's/"backgroundcolor": \[0.25, 0.3, 0.4\]/"backgroundcolor": [0.6, 0.35, 0.2]/' \
    "$SCENE_SOURCE" >"$changed_scene"
  cmp -s "$SCENE_SOURCE" "$changed_scene" && { fail "the scene edit changed nothing"; return; }
  offline "$SCRATCH/offline-original.png"
  "$RAYTRACER" "$changed_scene" "$SCRATCH/offline-final.png" --size $SIZE --spp $SPP -q \
    --shader-dir "$edited" || fail "offline render with edited shaders"

  # The viewer runs until SIGTERM; its pid comes out through a file.
  local log="$SCRATCH/log" err="$SCRATCH/err"
  xvfb_run bash -c "\"\$@\" & echo \$! >'$SCRATCH/pid'; wait \$!" viewer \
    "$RAYTRACER" view "$scene" --size $SIZE --max-spp $SPP --spp-per-frame 1 --no-overlay \
    --validation --verbose --shader-dir "$shaders" --screenshot "$SCRATCH/final.png" \
    >"$log" 2>"$err" &
  local runner=$!
  local deadline=$((SECONDS + 30))
  while [[ ! -s $SCRATCH/pid ]] && ((SECONDS < deadline)); do sleep 0.1; done
  VIEWER_PID=$(cat "$SCRATCH/pid" 2>/dev/null)
  if [[ -z $VIEWER_PID ]]; then
    fail "the viewer did not start"
    return
  fi

  if ! wait_for "$log" "^done: spp=$SPP " 1 60; then
    kill "$VIEWER_PID" 2>/dev/null
    wait "$runner"
    return
  fi
  # 1. A good edit (saved by rename): reloads, restarts, shows the new shading.
  edit "$shaders/trace.comp" "$swap"
  wait_for "$log" "^reload: ok" 1 60
  wait_for "$log" "^reload: presented" 1 30
  wait_for "$log" "^done: spp=$SPP " 2 60
  # 2. A syntax error (saved in place) in an included file: reported with
  # file:line, the last good kernel keeps rendering.
  echo "this is not glsl;" >>"$shaders/shading.glsl"
  local line
  line=$(wc -l <"$shaders/shading.glsl")
  wait_for "$err" "^reload: error shading\.glsl:$line: error" 1 60
  local frames
  frames=$(grep -c '^frame ' "$log")
  wait_for "$log" '^frame ' $((frames + 5)) 30
  # 3. A scene edit while the shaders are broken cannot be built: reported,
  # and applied as soon as the shaders are fixed.
  cp "$changed_scene" "$scene.tmp" && mv "$scene.tmp" "$scene"
  wait_for "$err" "^scene: error .*could not be built" 1 60
  cp "$edited/shading.glsl" "$shaders/shading.glsl"
  wait_for "$log" "^reload: ok" 2 60
  wait_for "$log" "^scene: reloaded" 1 60
  wait_for "$log" "^done: spp=$SPP " 3 60
  # 4. A broken scene file is reported and kept out.
  echo "{ broken" >"$scene"
  wait_for "$err" "^scene: error .*scene\.json: byte" 1 30
  frames=$(grep -c '^frame ' "$log")
  wait_for "$log" '^frame ' $((frames + 3)) 30

  kill -TERM "$VIEWER_PID"
  wait "$runner"
  local status=$?
  VIEWER_PID=
  [[ $status -eq 0 ]] || fail "viewer exit status $status after SIGTERM: $(grep -v '^reload: error\|^scene: error' "$err")"
  grep -h "^reload: \|^scene: " "$log" "$err"
  compare "final vs offline (edited shaders, edited scene)" "$SCRATCH/final.png" \
    "$SCRATCH/offline-final.png" --min-psnr 40 --max-diff 2
  compare "final vs offline (original)" "$SCRATCH/final.png" "$SCRATCH/offline-original.png" \
    --max-psnr 30
}

case $CASE in
  cli) case_cli ;;
  offscreen-match) case_offscreen_match ;;
  orbit) case_orbit ;;
  resize) case_resize ;;
  hot-reload) case_hot_reload ;;
  *)
    echo "unknown case $CASE"
    exit 2
    ;;
esac
if [[ $failed -gt 0 ]]; then
  echo "$failed check(s) failed; files in $SCRATCH"
  exit 1
fi
echo "viewer $CASE: all checks passed"
