// Scene buffers shared by every kernel that traces rays (set 0).
#ifndef RT_BINDINGS_GLSL
#define RT_BINDINGS_GLSL

layout(std430, set = 0, binding = RT_BINDING_SCENE_INFO) readonly buffer SceneInfoBuffer {
  GpuSceneInfo sceneInfo;
};
layout(std430, set = 0, binding = RT_BINDING_PRIMITIVES) readonly buffer PrimitiveBuffer {
  GpuPrimitive primitives[];
};
layout(std430, set = 0, binding = RT_BINDING_BVH_NODES) readonly buffer BvhNodeBuffer {
  GpuBvhNode bvhNodes[];
};
layout(std430, set = 0, binding = RT_BINDING_MATERIALS) readonly buffer MaterialBuffer {
  GpuMaterial materials[];
};
layout(std430, set = 0, binding = RT_BINDING_POINT_LIGHTS) readonly buffer PointLightBuffer {
  GpuPointLight pointLights[];
};

#endif
