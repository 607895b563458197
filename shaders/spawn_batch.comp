#version 460
// Test kernel for ray origins: each probe traces a ray to its closest hit,
// spawns a second ray there the way the renderer does (hitPoint and
// spawnRay), and traces that one too. Probe i reads rays[2i] (the first ray)
// and the direction of rays[2i + 1]; it writes hits[2i] and hits[2i + 1],
// the second with the spawned origin in `normal` when it hit nothing.
#extension GL_GOOGLE_include_directive : require

#include "gpu_types.h"

layout(local_size_x = RT_BATCH_WORKGROUP_SIZE) in;

layout(push_constant) uniform BatchParamsBlock { GpuBatchParams batch; };

layout(std430, set = 0, binding = RT_BINDING_RAYS) readonly buffer RayBuffer { GpuRay rays[]; };
layout(std430, set = 0, binding = RT_BINDING_HITS) writeonly buffer HitBuffer { GpuHit hits[]; };

#include "traverse.glsl"
#include "geometry.glsl"

GpuHit record(bool found, SurfaceHit hit) {
  GpuHit result;
  result.t = found ? hit.t : -1.0;
  result.normal = hit.normal;
  result.primitiveIndex = hit.primitiveIndex;
  result.shapeIndex = found ? primitiveInfo(hit.primitiveIndex).z : 0xffffffffu;
  result.occluded = 0u;
  result.pad0 = 0u;
  return result;
}

void main() {
  loadSceneInfo();
  uint probe = gl_GlobalInvocationID.x;
  if (probe >= batch.rayCount) return;
  GpuRay first = rays[2u * probe];
  Ray ray = Ray(first.origin, normalize(first.direction));
  SurfaceHit hit;
  bool found = closestHit(ray, first.tMin, first.tMax, hit);
  hits[2u * probe] = record(found, hit);
  GpuHit second = record(false, hit);
  if (found) {
    vec4 point = hitPoint(ray, hit);
    vec3 leaving = normalize(rays[2u * probe + 1u].direction);
    Ray spawned = spawnRay(point.xyz, point.w, hit.normal, leaving);
    SurfaceHit again;
    bool hitAgain = closestHit(spawned, 0.0, RT_FAR, again);
    second = record(hitAgain, again);
    if (!hitAgain) second.normal = spawned.origin;
    second.occluded = occluded(spawned, 0.0, RT_FAR) ? 1u : 0u;
  }
  hits[2u * probe + 1u] = second;
}
