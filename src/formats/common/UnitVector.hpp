// Normalising vectors read from files, which may be tiny (denormal) or huge.
#pragma once

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace rt {

// Scales `v` to unit length and returns true; returns false (leaving `v`
// alone) when it is zero or not finite. Dividing by the largest component
// first keeps the squares inside glm::length clear of float underflow and
// overflow: (2e-39, 2e-39, 1e-39) comes out unit length instead of 9% long,
// and (1e38, 1e38, 0) instead of being lost to infinity.
inline bool normalizeInPlace(glm::vec3& v) {
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) return false;
  const float largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  if (!(largest > 0.0f)) return false;
  const glm::vec3 scaled = v / largest;
  v = scaled / glm::length(scaled);
  return true;
}

}  // namespace rt
