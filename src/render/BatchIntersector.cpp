#include "render/BatchIntersector.hpp"

namespace rt {

std::vector<gpu::GpuHit> BatchIntersector::intersect(const std::vector<gpu::GpuRay>& rays) {
  std::vector<gpu::GpuRay> framed;
  framed.reserve(rays.size());
  for (const gpu::GpuRay& ray : rays) framed.push_back(kernel_.toFrame(ray));
  return kernel_.run<gpu::GpuHit>(framed, rays.size());
}

}  // namespace rt
