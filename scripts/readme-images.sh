#!/usr/bin/env bash
# Renders the README's scene images (assets/readme/) with this build, the
# command of each in one place, so that they show what the renderer draws
# today: run it after a change that alters images (conventions,
# shading, sampling) and look at the result before committing it. On
# demand, never from the tests; about six minutes on two cores, most of it
# the path-traced Cornell box at 1024 samples. The plots and adaptive
# sampling's images come from bench/run-convergence.sh and
# bench/run-adaptive.sh. Needs ../shared beside the checkout (or
# SHARED_DIR) and, for the viewer's screenshot, xvfb-run.
#   scripts/readme-images.sh [NAME...]   (default: all; e.g. default bunny)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
shared=$(cd "${SHARED_DIR:-$root/../shared}" && pwd)
bash "$root/scripts/build.sh" --target raytracer
raytracer=$root/build/raytracer
images=$root/assets/readme
scenes=$shared/scene-format
official=$scenes/official
freddie=$scenes/student/TsFreddie__RayTracer/examples
julie=$scenes/student/julie-o__CG-cw
khronos=$shared/assets/gltf/khronos-sample-assets
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

render() {  # NAME SCENE [OPTIONS...]
  local name=$1 scene=$2
  shift 2
  "$raytracer" "$scene" "$images/$name.png" "$@" 2>&1 | tail -n 1
}

# A copy of SCENE in the work folder beside the files it refers to (so
# that relative texture paths still resolve), with sed EXPRESSION applied.
edited_copy() {  # SCENE EXPRESSION NAME
  local folder
  folder=$work/$3
  mkdir -p "$folder"
  for entry in "$(dirname "$1")"/*; do ln -s "$entry" "$folder/"; done
  rm "$folder/$(basename "$1")"
  sed -e "$2" "$1" >"$folder/$(basename "$1")"
  echo "$folder/$(basename "$1")"
}

make_image() {  # NAME
  case $1 in
    default) render default "$root/scenes/default.json" ;;
    path-of-light-example)
      render path-of-light-example "$official/cg-path-of-light-2021-2023/examples/example.json" \
        --size 400x400 ;;
    rendering-mirror-image)
      render rendering-mirror-image "$official/cgr-2023-2024/mirror_image.json" --size 600x400 ;;
    rendering-binary)
      render rendering-binary "$official/cgr-2023-2024/binary_primitves.json" --size 300x200 ;;
    rendering-phong-scene)  # the file asks for binary mode
      render rendering-phong-scene \
        "$(edited_copy "$official/cgr-2023-2024/scene.json" \
          's/"rendermode" *: *"binary"/"rendermode":"phong"/' phong)" --size 600x400 ;;
    bunny)
      sed "s#@BUNNY@#$shared/assets/ply/stanford-bunny/bunny/reconstruction/bun_zipper.ply#" \
        "$root/bench/bunny.json.in" >"$work/bunny.json"
      render bunny "$work/bunny.json" --size 400x400 ;;
    gltf-duck) render gltf-duck "$khronos/Duck/glTF-Binary/Duck.glb" --size 400x300 ;;
    gltf-vertex-colors)
      render gltf-vertex-colors "$khronos/BoxVertexColors/glTF-Binary/BoxVertexColors.glb" \
        --size 300x225 ;;
    gltf-helmet)
      render gltf-helmet "$khronos/DamagedHelmet/glTF-Binary/DamagedHelmet.glb" --size 400x300 ;;
    gltf-alpha-mask)  # glass spheres; the "with opacity" columns cut by alpha masks
      render gltf-alpha-mask "$khronos/TransmissionTest/glTF/TransmissionTest.gltf" \
        --size 640x360 ;;
    cornell-pathtraced)
      render cornell-pathtraced "$root/scenes/cornell-pathtraced.json" --size 400x400 --spp 1024 ;;
    cornell-clamped)
      render cornell-clamped "$root/scenes/cornell-pathtraced.json" --size 400x400 --spp 256 \
        --clamp-indirect 4 ;;
    student-julie-o-demo) render student-julie-o-demo "$julie/demo.json" --size 400x400 --spp 32 ;;
    student-julie-o-pitched)  # its lookat direction pitched 10 degrees down instead of 25
      render student-julie-o-pitched \
        "$(edited_copy "$julie/demo.json" 's/"lookat": \[0.0, 4.5, -2.1\]/"lookat": [0.0, 4.5, -0.79]/' \
          julie)" --size 400x400 --spp 32 ;;
    student-softshadow) render student-softshadow "$freddie/softshadow_test.json" ;;
    student-dof) render student-dof "$freddie/dof_test.json" ;;
    study-arealight) render study-arealight "$root/scenes/study-arealight.json" ;;
    obj-crate) render obj-crate "$root/assets/models/crate.obj" --size 480x360 ;;
    obj-cornell-box) render obj-cornell-box "$root/assets/models/cornell-box.obj" --size 400x300 ;;
    viewer)
      xvfb-run -a -s "-screen 0 1024x768x24" "$raytracer" view \
        "$official/cg-path-of-light-2021-2023/examples/example.json" --size 960x720 --frames 60 \
        --screenshot "$images/viewer.png" >/dev/null
      echo "viewer: $images/viewer.png" ;;
    *)
      echo "readme-images.sh: no image named '$1'" >&2
      return 1 ;;
  esac
}

all=(default path-of-light-example rendering-mirror-image rendering-binary rendering-phong-scene
  bunny gltf-duck gltf-vertex-colors gltf-helmet gltf-alpha-mask cornell-pathtraced cornell-clamped student-julie-o-demo
  student-julie-o-pitched student-softshadow student-dof study-arealight obj-crate obj-cornell-box
  viewer)
for name in "${@:-${all[@]}}"; do
  echo "== $name"
  make_image "$name"
done
