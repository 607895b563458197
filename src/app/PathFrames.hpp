// Frames of a viewer camera path rendered headless (raytracer SCENE OUT
// --camera-path FILE --frame N): the camera and image size the viewer has at
// frame N, replayed with the viewer's own orbit camera, so that an animation
// can be rendered frame by frame on many machines (rtfarm animate).
#pragma once

#include <cstdint>
#include <vector>

#include "scene/Scene.hpp"
#include "viewer/CameraPath.hpp"

namespace rt::cli {

// How many frames the path lasts: one per step, N for `wait N`.
uint32_t pathFrameCount(const std::vector<viewer::PathStep>& steps);

struct PathFrame {
  Camera camera;
  uint32_t width = 0;
  uint32_t height = 0;
};

// The view at frame `frame` (0: the first): every step up to and including
// that frame's applied to the scene's camera, on an image of width x height
// that `resize` steps change. `screenshot` and `save` are the viewer's own
// outputs and change nothing; `focus` picks a surface with the viewer's GPU
// query and is refused (rt::Error "FILE:LINE: ..."), as is a frame past the end.
PathFrame pathFrame(const Scene& scene, const std::vector<viewer::PathStep>& steps,
                    const std::string& pathFile, uint32_t frame, uint32_t width, uint32_t height);

}  // namespace rt::cli
