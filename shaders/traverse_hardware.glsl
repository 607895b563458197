// Scene queries through the driver's acceleration structures (--accel
// hardware, src/render/HardwareScene): GPUs with ray tracing units walk them
// in hardware. Included by traverse.glsl in place of the BVH walk, with the
// same interface and the same hits: mesh triangles are opaque hardware
// triangles (but for instances with alpha cutouts: candidates that
// alpha.glsl decides); spheres, cylinders and loose triangles are boxes whose
// candidates the renderer's own intersection code decides
// (testTopLevelItem), so every shape is hit exactly as the BVH path hits it.
// Instance encoding (HardwareScene.cpp): a mesh instance's custom index is
// its top-level primitive and its shader-binding-table offset the first item
// of its mesh's triangles; the box instance's custom index is the first
// loose primitive.
#ifndef RT_TRAVERSE_HARDWARE_GLSL
#define RT_TRAVERSE_HARDWARE_GLSL

#extension GL_EXT_ray_query : require

#include "hits.glsl"
#ifdef RT_FEATURE_ALPHA_CUTOUTS
#include "alpha.glsl"
#endif

layout(set = 0, binding = RT_BINDING_TLAS) uniform accelerationStructureEXT sceneTopLevel;

bool traverse(Ray worldRay, float tMin, inout float tMax, bool anyHit, out SurfaceHit hit) {
  clearHit(hit);
#ifdef RT_TALLY_RAYS
  ++raysTraced;
#endif
  if (sceneInfo.primitiveCount == 0u) return false;
#ifdef RT_FEATURE_ALPHA_CUTOUTS
  // Instances with cutouts are built non-opaque (HardwareScene.cpp): their
  // triangles come to the loop below as candidates.
  uint flags = anyHit ? gl_RayFlagsTerminateOnFirstHitEXT : 0u;
#else
  uint flags = gl_RayFlagsOpaqueEXT | (anyHit ? gl_RayFlagsTerminateOnFirstHitEXT : 0u);
#endif
  rayQueryEXT query;
  rayQueryInitializeEXT(query, sceneTopLevel, flags, 0xffu, worldRay.origin, tMin,
                        worldRay.direction, tMax);
  uint hitKind = RT_PRIM_TRIANGLE;
#ifdef RT_TOP_LEVEL_SHAPES
  ShearedRay frame = shearRay(worldRay.direction);
#endif
  while (rayQueryProceedEXT(query)) {
#ifdef RT_FEATURE_ALPHA_CUTOUTS
    if (rayQueryGetIntersectionTypeEXT(query, false) ==
        gl_RayQueryCandidateIntersectionTriangleEXT) {
      uint instance = uint(rayQueryGetIntersectionInstanceCustomIndexEXT(query, false));
      uint item = rayQueryGetIntersectionInstanceShaderBindingTableRecordOffsetEXT(query, false) +
                  uint(rayQueryGetIntersectionPrimitiveIndexEXT(query, false));
      vec2 barycentric = rayQueryGetIntersectionBarycentricsEXT(query, false);
      if (alphaCovers(instance, item, barycentric, worldRay)) {
        rayQueryConfirmIntersectionEXT(query);
        if (anyHit) rayQueryTerminateEXT(query);
      }
      continue;
    }
#endif
#ifdef RT_TOP_LEVEL_SHAPES
    // Only boxes come here (and triangles with cutouts, above). The nearest committed hit
    // so far bounds the candidate, as tMax does in the BVH walk.
    float limit = rayQueryGetIntersectionTypeEXT(query, true) ==
                          gl_RayQueryCommittedIntersectionNoneEXT
                      ? tMax
                      : rayQueryGetIntersectionTEXT(query, true);
    uint item = uint(rayQueryGetIntersectionInstanceCustomIndexEXT(query, false)) +
                uint(rayQueryGetIntersectionPrimitiveIndexEXT(query, false));
    uint kind = primitiveInfo(item).x;
    if (testTopLevelItem(item, kind, worldRay, frame, tMin, limit, hit)) {
      hitKind = kind;
      rayQueryGenerateIntersectionEXT(query, limit);
      if (anyHit) rayQueryTerminateEXT(query);
    }
#endif
  }
  uint committed = rayQueryGetIntersectionTypeEXT(query, true);
  if (committed == gl_RayQueryCommittedIntersectionNoneEXT) {
    hit.t = -1.0;
    return false;
  }
  // A generated hit is the last one testTopLevelItem recorded; a triangle
  // committed after it is nearer and replaces it.
  if (committed == gl_RayQueryCommittedIntersectionTriangleEXT) {
    hitKind = RT_PRIM_TRIANGLE;
    hit.primitiveIndex = uint(rayQueryGetIntersectionInstanceCustomIndexEXT(query, true));
    hit.triangleIndex =
        rayQueryGetIntersectionInstanceShaderBindingTableRecordOffsetEXT(query, true) +
        uint(rayQueryGetIntersectionPrimitiveIndexEXT(query, true));
    hit.barycentric = rayQueryGetIntersectionBarycentricsEXT(query, true);
  }
  hit.t = rayQueryGetIntersectionTEXT(query, true);
  tMax = hit.t;
  completeHitNormal(worldRay, hitKind, hit);
  return true;
}

#endif
