#version 460
// Test kernel: closest-hit and any-hit queries for a batch of rays, through
// the same intersection and traversal code the renderer uses.
#extension GL_GOOGLE_include_directive : require

#include "gpu_types.h"

layout(local_size_x = RT_BATCH_WORKGROUP_SIZE) in;

layout(push_constant) uniform BatchParamsBlock { GpuBatchParams batch; };

layout(std430, set = 0, binding = RT_BINDING_RAYS) readonly buffer RayBuffer { GpuRay rays[]; };
layout(std430, set = 0, binding = RT_BINDING_HITS) writeonly buffer HitBuffer { GpuHit hits[]; };

#include "traverse.glsl"

void main() {
  loadSceneInfo();
  uint index = gl_GlobalInvocationID.x;
  if (index >= batch.rayCount) return;
  GpuRay query = rays[index];
  Ray ray = Ray(query.origin, normalize(query.direction));
  SurfaceHit hit;
  GpuHit result;
  bool found = closestHit(ray, query.tMin, query.tMax, hit);
  result.t = found ? hit.t : -1.0;
  result.normal = hit.normal;
  result.primitiveIndex = hit.primitiveIndex;
  result.shapeIndex = found ? hitShape(hit) : 0xffffffffu;
  result.occluded = occluded(ray, query.tMin, query.tMax) ? 1u : 0u;
  result.pad0 = 0u;
  hits[index] = result;
}
