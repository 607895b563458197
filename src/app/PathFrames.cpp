#include "app/PathFrames.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "app/CommandLine.hpp"
#include "scene/SceneBounds.hpp"
#include "util/Error.hpp"
#include "viewer/OrbitCamera.hpp"

namespace rt::cli {
namespace {

using viewer::PathStep;

uint32_t windowSide(float value) {
  return static_cast<uint32_t>(std::clamp(value, 1.0f, float(kMaxImageSide)));
}

// The viewer's Viewer::applyPathStep, on the parts a headless render has.
void applyStep(const PathStep& step, const std::string& pathFile, viewer::OrbitCamera& camera,
               PathFrame& frame) {
  using Kind = PathStep::Kind;
  const std::vector<float>& v = step.values;
  switch (step.kind) {
    case Kind::Orbit: camera.orbit(v[0], v[1]); break;
    case Kind::Pan: camera.pan({v[0], v[1]}, static_cast<float>(frame.height)); break;
    case Kind::Zoom: camera.zoom(v[0]); break;
    case Kind::Fly: camera.fly({v[0], v[1], v[2]}); break;
    case Kind::LookAt: camera.lookAt({v[0], v[1], v[2]}, {v[3], v[4], v[5]}); break;
    case Kind::Lens: camera.setLens(v[0], v[1]); break;
    case Kind::Reset: camera.reset(); break;
    case Kind::Resize:
      frame.width = windowSide(v[0]);
      frame.height = windowSide(v[1]);
      break;
    case Kind::Focus:
      throw Error(
          fmt::format("{}:{}: 'focus' needs the viewer's surface picking; give the "
                      "distance with 'lens RADIUS DISTANCE' to render frames",
                      pathFile, step.line));
    case Kind::Screenshot:
    case Kind::Save:
    case Kind::Wait: break;
  }
}

}  // namespace

uint32_t pathFrameCount(const std::vector<PathStep>& steps) {
  uint64_t frames = 0;
  for (const PathStep& step : steps) frames += step.kind == PathStep::Kind::Wait ? step.frames : 1;
  return static_cast<uint32_t>(std::min<uint64_t>(frames, UINT32_MAX));
}

PathFrame pathFrame(const Scene& scene, const std::vector<PathStep>& steps,
                    const std::string& pathFile, uint32_t frame, uint32_t width, uint32_t height) {
  const uint32_t frames = pathFrameCount(steps);
  if (frame >= frames) {
    throw Error(fmt::format("--frame {}: {} has {} frame(s), 0..{}", frame, pathFile, frames,
                            frames == 0 ? 0 : frames - 1));
  }
  viewer::OrbitCamera camera;
  BoundingSphere bounds = boundingSphere(scene);
  camera.setHome(scene.camera, bounds.center, bounds.radius);
  PathFrame result{scene.camera, width, height};
  // The player hands out the step of each frame as the viewer's loop asks.
  viewer::CameraPathPlayer player(steps);
  for (uint32_t shown = 0; shown <= frame; ++shown) {
    if (const PathStep* step = player.next()) applyStep(*step, pathFile, camera, result);
  }
  result.camera = camera.camera();
  return result;
}

}  // namespace rt::cli
