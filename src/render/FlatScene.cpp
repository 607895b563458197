#include "render/FlatScene.hpp"

#include <cmath>
#include <variant>

#include "bvh/Bvh.hpp"
#include "render/Conventions.hpp"

namespace rt {
namespace {

// The colour of hit pixels in `rendermode: binary` (misses show the background).
constexpr glm::vec3 kBinaryHitColor{1.0f, 0.0f, 0.0f};

gpu::GpuPrimitive makeTriangle(const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2) {
  gpu::GpuPrimitive prim{};
  prim.kind = RT_PRIM_TRIANGLE;
  prim.a = glm::vec4(v0, 0.0f);
  prim.b = glm::vec4(v1 - v0, 0.0f);
  prim.c = glm::vec4(v2 - v0, 0.0f);
  return prim;
}

struct PrimitiveSink {
  const Scene& scene;
  std::vector<gpu::GpuPrimitive>& out;
  void operator()(const Sphere& s) const {
    gpu::GpuPrimitive prim{};
    prim.kind = RT_PRIM_SPHERE;
    prim.a = glm::vec4(s.center, s.radius);
    out.push_back(prim);
  }
  void operator()(const Triangle& t) const { out.push_back(makeTriangle(t.v0, t.v1, t.v2)); }
  void operator()(const Quad& q) const {
    out.push_back(makeTriangle(q.v0, q.v1, q.v2));
    out.push_back(makeTriangle(q.v0, q.v2, q.v3));
  }
  void operator()(const Cylinder& c) const {
    gpu::GpuPrimitive prim{};
    prim.kind = RT_PRIM_CYLINDER;
    prim.a = glm::vec4(c.center, c.radius);
    prim.b = glm::vec4(c.axis, c.halfHeight);
    out.push_back(prim);
  }
  void operator()(const MeshInstance& instance) const {
    const TriangleMesh& mesh = scene.meshes.at(instance.mesh);
    std::vector<glm::vec3> world;
    world.reserve(mesh.positions.size());
    for (const glm::vec3& p : mesh.positions) {
      world.push_back(glm::vec3(instance.objectToWorld * glm::vec4(p, 1.0f)));
    }
    for (const glm::uvec3& face : mesh.faces) {
      out.push_back(makeTriangle(world[face.x], world[face.y], world[face.z]));
    }
  }
};

Aabb primitiveBounds(const gpu::GpuPrimitive& prim) {
  Aabb box;
  glm::vec3 a(prim.a);
  if (prim.kind == RT_PRIM_SPHERE) {
    box.grow(a - glm::vec3(prim.a.w));
    box.grow(a + glm::vec3(prim.a.w));
  } else if (prim.kind == RT_PRIM_TRIANGLE) {
    box.grow(a);
    box.grow(a + glm::vec3(prim.b));
    box.grow(a + glm::vec3(prim.c));
  } else {
    // Cylinder: the caps' discs bound it; a disc of radius r around axis n
    // extends r * sqrt(1 - n_i^2) along axis i.
    glm::vec3 axis(prim.b);
    glm::vec3 capOffset = axis * prim.b.w;
    glm::vec3 discExtent = prim.a.w * glm::sqrt(glm::max(glm::vec3(0.0f), 1.0f - axis * axis));
    for (float side : {-1.0f, 1.0f}) {
      box.grow(a + side * capOffset - discExtent);
      box.grow(a + side * capOffset + discExtent);
    }
  }
  return box;
}

std::vector<gpu::GpuPrimitive> collectPrimitives(const Scene& scene) {
  std::vector<gpu::GpuPrimitive> primitives;
  for (uint32_t shapeIndex = 0; shapeIndex < scene.shapes.size(); ++shapeIndex) {
    const Shape& shape = scene.shapes[shapeIndex];
    size_t first = primitives.size();
    std::visit(PrimitiveSink{scene, primitives}, shape.geometry);
    for (size_t i = first; i < primitives.size(); ++i) {
      primitives[i].materialIndex = shape.material;
      primitives[i].shapeIndex = shapeIndex;
    }
  }
  return primitives;
}

void addBvh(FlatScene& flat) {
  std::vector<Aabb> bounds;
  bounds.reserve(flat.primitives.size());
  for (const auto& prim : flat.primitives) bounds.push_back(primitiveBounds(prim));
  BvhBuildOptions options;
  options.maxDepth = RT_BVH_MAX_DEPTH;
  Bvh bvh = buildBvh(bounds, options);
  std::vector<gpu::GpuPrimitive> ordered;
  ordered.reserve(flat.primitives.size());
  for (uint32_t index : bvh.primitiveOrder) ordered.push_back(flat.primitives[index]);
  flat.primitives = std::move(ordered);
  for (const BvhNode& node : bvh.nodes) {
    flat.bvhNodes.push_back({node.bounds.min, node.firstIndex, node.bounds.max, node.count});
  }
  flat.bvhDepth = bvh.depth;
}

gpu::GpuMaterial toGpu(const Material& m) {
  return {m.diffuseColor,     m.kd,           m.specularColor, m.ks,
          m.specularExponent, m.reflectivity, m.transmission,  m.ior};
}

}  // namespace

void fillCamera(const Camera& camera, uint32_t width, uint32_t height, gpu::GpuSceneInfo& info) {
  glm::vec3 forward = glm::normalize(camera.forward);
  glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
  info.cameraPosition = camera.position;
  info.cameraForward = forward;
  info.cameraRight = right;
  info.cameraUp = glm::cross(right, forward);
  info.tanHalfFovY = std::tan(glm::radians(camera.fovYDegrees) * 0.5f);
  info.aspect = static_cast<float>(width) / static_cast<float>(height);
  info.apertureRadius = camera.type == CameraType::ThinLens ? camera.apertureRadius : 0.0f;
  info.focusDistance = camera.focusDistance;
  info.width = width;
  info.height = height;
}


FlatScene flattenScene(const Scene& scene, const FlattenOptions& options) {
  FlatScene flat;
  uint32_t width = options.width ? options.width : scene.camera.width;
  uint32_t height = options.height ? options.height : scene.camera.height;
  fillCamera(scene.camera, width, height, flat.info);
  for (const Material& m : scene.materials) {
    flat.materials.push_back(toGpu(m));
    if (m.diffuseTexture >= 0 && flat.warnings.empty()) {
      flat.warnings.push_back(
          scene.sourcePath.string() +
          ": textures are not rendered yet; the diffuse colour is used instead");
    }
  }
  for (const PointLight& light : scene.pointLights) {
    flat.pointLights.push_back(
        {light.position, 0.0f, light.diffuseIntensity, 0.0f, light.specularIntensity, 0.0f});
  }
  flat.primitives = collectPrimitives(scene);
  addBvh(flat);

  LightingConventions conventions = lightingConventionsFor(scene.family, options.shading);
  gpu::GpuSceneInfo& info = flat.info;
  info.backgroundColor = scene.backgroundColor;
  info.maxBounces = scene.settings.maxBounces;
  info.binaryHitColor = kBinaryHitColor;
  info.renderMode = scene.settings.mode == RenderMode::Binary ? RT_MODE_BINARY : RT_MODE_PHONG;
  info.pointLightCount = static_cast<uint32_t>(flat.pointLights.size());
  info.primitiveCount = static_cast<uint32_t>(flat.primitives.size());
  info.bvhNodeCount = static_cast<uint32_t>(flat.bvhNodes.size());
  info.lightFalloff = conventions.falloff;
  info.lightScale = conventions.lightScale;
  info.shadingModel =
      conventions.shading == ShadingModel::Coursework ? RT_SHADING_COURSEWORK : RT_SHADING_STANDARD;
  return flat;
}

}  // namespace rt
