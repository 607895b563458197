// Scene buffers shared by every kernel that traces rays (set 0).
#ifndef RT_BINDINGS_GLSL
#define RT_BINDINGS_GLSL

// A uniform block: GpuSceneInfo has only vec3 + scalar pairs and scalars, so
// its std140 layout is its std430 one. (CPU drivers read storage buffers
// lane by lane inside loops and branches, even at a shared index.)
layout(std140, set = 0, binding = RT_BINDING_SCENE_INFO) uniform SceneInfoBlock {
  GpuSceneInfo sceneInfo;
};
// Primitives and BVH nodes are read through texel buffers (RGBA32F, records
// of whole texels): CPU drivers such as lavapipe gather texels with vector
// loads but read storage buffers at divergent indices one lane at a time,
// which made traversal several times slower.
layout(set = 0, binding = RT_BINDING_PRIMITIVES) uniform samplerBuffer primitiveTexels;
layout(set = 0, binding = RT_BINDING_BVH_NODES) uniform usamplerBuffer bvhNodeTexels;

// Shading data of top-level primitive `index` (GpuPrimitive), texel `row`
// (0..3): a, b, c, then kind/material/shape/flags.
vec4 primitiveRow(uint index, uint row) {
  return texelFetch(primitiveTexels, int(index * RT_TEXELS_PER_PRIMITIVE + row));
}

uvec4 primitiveInfo(uint index) { return floatBitsToUint(primitiveRow(index, 3u)); }

GpuPrimitive loadPrimitive(uint index) {
  uvec4 info = primitiveInfo(index);
  return GpuPrimitive(primitiveRow(index, 0u), primitiveRow(index, 1u), primitiveRow(index, 2u),
                      info.x, info.y, info.z, info.w);
}

// Texel `row` (0..1) of BVH node `index` (see GpuBvhNode).
uvec4 nodeRow(uint index, uint row) {
  return texelFetch(bvhNodeTexels, int(index * RT_TEXELS_PER_BVH_NODE + row));
}

layout(set = 0, binding = RT_BINDING_ITEMS) uniform samplerBuffer itemTexels;

// Texel `row` (0..2) of leaf item `index` (see GpuItem).
vec4 itemRow(uint index, uint row) {
  return texelFetch(itemTexels, int(index * RT_TEXELS_PER_ITEM + row));
}

layout(std430, set = 0, binding = RT_BINDING_MATERIALS) readonly buffer MaterialBuffer {
  GpuMaterial materials[];
};
layout(std430, set = 0, binding = RT_BINDING_POINT_LIGHTS) readonly buffer PointLightBuffer {
  GpuPointLight pointLights[];
};

#endif
