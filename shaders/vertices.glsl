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

GpuVertex loadVertex(uint index) {
  vec4 normalU = vertexRow(index, 0u);
  vec4 colorV = vertexRow(index, 1u);
  return GpuVertex(normalU.xyz, normalU.w, colorV.xyz, colorV.w);
}
#endif

#endif
