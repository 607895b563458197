#include "scene/SceneBounds.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <variant>

namespace rt {
namespace {

// Coordinates must resolve the scene's extent into at least this many steps.
// scenes/default.json at 800x600, 4 spp, moved 1e9 away and scaled down
// until it had 2^17.2, 2^18.8 and 2^20.5 steps across it, rendered at 57.7,
// 61.8 and 67.0 dB (8-bit PSNR) against itself at the origin: 2^19 keeps
// images above 60 dB (the GPU's floats resolve 2^24 steps).
constexpr double kLeastStepsAcross = 0x1p19;

void addBall(WorldBounds& box, const WorldPoint& center, double radius) {
  box.grow(center - glm::dvec3(radius));
  box.grow(center + glm::dvec3(radius));
}

// The box of `box` placed by `transform`: its eight corners, transformed.
void addPlacedBox(const WorldBounds& box, const WorldTransform& transform, WorldBounds& out) {
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 p(corner & 1 ? box.hi.x : box.lo.x, corner & 2 ? box.hi.y : box.lo.y,
                       corner & 4 ? box.hi.z : box.lo.z);
    out.grow(WorldPoint(transform * glm::dvec4(p, 1.0)));
  }
}

// `meshBoxes` (each mesh's object-space box): mesh instances are bounded by
// their placed boxes, 8 points each however large the mesh; without them,
// by every placed vertex (the tight box).
void addShape(const Scene& scene, const Geometry& geometry,
              const std::vector<WorldBounds>* meshBoxes, WorldBounds& box) {
  std::visit(
      [&](const auto& g) {
        using T = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<T, Sphere>) addBall(box, g.center, g.radius);
        if constexpr (std::is_same_v<T, Triangle>) {
          for (const WorldPoint& v : {g.v0, g.v1, g.v2}) box.grow(v);
        }
        if constexpr (std::is_same_v<T, Quad>) {
          for (const WorldPoint& v : {g.v0, g.v1, g.v2, g.v3}) box.grow(v);
        }
        if constexpr (std::is_same_v<T, Cylinder>) {
          addBall(box, g.center, double(g.radius) + double(g.halfHeight));
        }
        if constexpr (std::is_same_v<T, MeshInstance>) {
          if (g.mesh >= scene.meshes.size()) return;
          if (meshBoxes) return addPlacedBox((*meshBoxes)[g.mesh], g.objectToWorld, box);
          for (const glm::vec3& p : scene.meshes[g.mesh].positions) {
            box.grow(WorldPoint(g.objectToWorld * glm::dvec4(glm::dvec3(p), 1.0)));
          }
        }
      },
      geometry);
}

double largestMagnitude(const glm::dvec3& v) {
  return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

}  // namespace

double WorldBounds::radius() const {
  const double radius = empty() ? 0.0 : 0.5 * glm::length(hi - lo);
  return radius > 0.0 ? radius : 1.0;
}

WorldBounds shapeBounds(const Scene& scene) {
  WorldBounds box;
  for (const Shape& shape : scene.shapes) addShape(scene, shape.geometry, nullptr, box);
  return box;
}

BoundingSphere boundingSphere(const Scene& scene) {
  const WorldBounds box = shapeBounds(scene);
  if (box.empty()) {
    return {scene.camera.position + glm::dvec3(glm::normalize(scene.camera.forward)), 1.0};
  }
  return {box.center(), box.radius()};
}

std::optional<std::string> precisionProblem(const Scene& scene) {
  // Every render asks: a mesh's vertices are read once, not once per placement.
  std::vector<WorldBounds> meshBoxes(scene.meshes.size());
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    for (const glm::vec3& p : scene.meshes[i].positions) meshBoxes[i].grow(glm::dvec3(p));
  }
  WorldBounds box;
  for (const Shape& shape : scene.shapes) addShape(scene, shape.geometry, &meshBoxes, box);
  if (box.empty()) return std::nullopt;
  const double extent = glm::length(box.hi - box.lo);
  const double farthest = std::max(largestMagnitude(box.lo), largestMagnitude(box.hi));
  // The spacing of doubles at the scene's farthest coordinate.
  const double step = std::nextafter(farthest, INFINITY) - farthest;
  if (!(extent > 0.0) || extent >= kLeastStepsAcross * step) return std::nullopt;
  return fmt::format(
      "the shapes are {:.3g} across but {:.3g} from the world origin, where double precision "
      "places coordinates only to {:.3g} (fewer than 2^19 steps across the scene): move them "
      "nearer the origin",
      extent, farthest, step);
}

}  // namespace rt
