// Where a scene's geometry lies in the world, in double precision: the box
// around its shapes, the bounding sphere that places the viewer's pivot and
// frames model files, and whether double precision can place it at all.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "scene/Scene.hpp"

namespace rt {

// An axis-aligned world box; empty until grown.
struct WorldBounds {
  glm::dvec3 lo{std::numeric_limits<double>::max()};
  glm::dvec3 hi{std::numeric_limits<double>::lowest()};

  bool empty() const { return lo.x > hi.x; }
  void grow(const glm::dvec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  WorldPoint center() const { return empty() ? WorldPoint(0.0) : 0.5 * (lo + hi); }
  double radius() const;  // of the bounding sphere; 1 for an empty box or a single point
};

// The box around every shape of the scene (empty without shapes).
WorldBounds shapeBounds(const Scene& scene);

struct BoundingSphere {
  WorldPoint center{0.0};
  double radius = 1.0;
};

// Of the scene's shapes; for a scene without shapes, a unit sphere in front
// of its camera.
BoundingSphere boundingSphere(const Scene& scene);

// Why double precision cannot place the scene's geometry as finely as the
// GPU draws it: a scene so small and so far from the world origin that its
// coordinates take fewer than 2^19 steps across it (a 1e-3 scene at 1e9).
// nullopt when it can. Mesh instances count by their placed object-space
// boxes (the tight box when the placement only moves and scales), so the
// check reads each mesh once however often it is placed.
std::optional<std::string> precisionProblem(const Scene& scene);

}  // namespace rt
