#include "render/BatchIntersector.hpp"

namespace rt {

std::vector<gpu::GpuHit> BatchIntersector::intersect(const std::vector<WorldRay>& rays) {
  std::vector<gpu::GpuRay> framed;
  framed.reserve(rays.size());
  for (const WorldRay& ray : rays) framed.push_back(kernel_.toFrame(ray));
  return kernel_.run<gpu::GpuHit>(framed, rays.size());
}

std::vector<gpu::GpuHit> BatchIntersector::intersect(const std::vector<gpu::GpuRay>& rays) {
  std::vector<WorldRay> world;
  world.reserve(rays.size());
  for (const gpu::GpuRay& ray : rays) {
    world.push_back({WorldPoint(ray.origin), ray.direction, ray.tMax});
  }
  return intersect(world);
}

}  // namespace rt
