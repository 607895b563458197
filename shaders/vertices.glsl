// Vertex records of triangles that carry more than their corners (see
// GpuVertex): shading interpolates them, the walk reads their texture
// coordinates for alpha cutouts.
#ifndef RT_VERTICES_GLSL
#define RT_VERTICES_GLSL

#include "gpu_types.h"
#include "bindings.glsl"

#ifdef RT_FEATURE_VERTICES
RT_FLOAT_ROWS(RT_BINDING_VERTICES, vertexTexels)

// Texel `row` (0..1) of vertex `index` (see GpuVertex): normal/u, then colour/v.
vec4 vertexRow(uint index, uint row) {
  return RT_ROW(vertexTexels, index * RT_TEXELS_PER_VERTEX + row);
}

vec2 vertexUv(uint index) { return vec2(vertexRow(index, 0u).w, vertexRow(index, 1u).w); }

// The vertex records of a triangle's corners: the w of its three corner rows
// (a mesh triangle's GpuItem, a loose triangle's GpuPrimitive a, b, c).
uvec3 triangleVertices(vec4 row0, vec4 row1, vec4 row2) {
  return floatBitsToUint(vec3(row0.w, row1.w, row2.w));
}

GpuVertex loadVertex(uint index) {
  vec4 normalU = vertexRow(index, 0u);
  vec4 colorV = vertexRow(index, 1u);
  return GpuVertex(normalU.xyz, normalU.w, colorV.xyz, colorV.w);
}
#endif

#endif
