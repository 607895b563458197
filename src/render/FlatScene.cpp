#include "render/FlatScene.hpp"

#include <cmath>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/packing.hpp>
#include <initializer_list>
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
  prim.b = glm::vec4(v1, 0.0f);
  prim.c = glm::vec4(v2, 0.0f);
  return prim;
}

// Points a triangle at three GpuVertex records (indices stored as float bits).
void attachVertices(gpu::GpuPrimitive& prim, glm::uvec3 indices, bool smooth) {
  prim.a.w = glm::uintBitsToFloat(indices.x);
  prim.b.w = glm::uintBitsToFloat(indices.y);
  prim.c.w = glm::uintBitsToFloat(indices.z);
  prim.flags |= RT_PRIM_HAS_VERTICES | (smooth ? RT_PRIM_SMOOTH : 0u);
}

// UVs of a mesh without its own: spherical projection around the centre of
// its bounds, with the pole along the sphere-UV axis (like spheres).
glm::vec2 projectedUv(const glm::vec3& p, const glm::vec3& center, uint32_t pole) {
  glm::vec3 d = p - center;
  float length = glm::length(d);
  if (!(length > 0.0f)) return glm::vec2(0.0f);
  d /= length;
  float u = 0.5f + std::atan2(d[(pole + 2) % 3], d[(pole + 1) % 3]) / (2.0f * glm::pi<float>());
  float v = std::acos(glm::clamp(d[pole], -1.0f, 1.0f)) / glm::pi<float>();
  return {u, v};
}

// Turns shapes into GPU primitives, and adds vertex records where a
// triangle needs more than its corners: smooth normals or texture coordinates.
struct PrimitiveSink {
  const Scene& scene;
  const Material& material;
  uint32_t uvPole;
  FlatScene& flat;

  void operator()(const Sphere& s) const {
    gpu::GpuPrimitive prim{};
    prim.kind = RT_PRIM_SPHERE;
    prim.a = glm::vec4(s.center, s.radius);
    flat.primitives.push_back(prim);
  }
  // A lone triangle's UVs are its barycentric coordinates: (0,0), (1,0), (0,1).
  void operator()(const Triangle& t) const {
    flat.primitives.push_back(makeTriangle(t.v0, t.v1, t.v2));
  }
  // Quads map the unit square onto v0 v1 v2 v3 (v0 at uv (0,0), v1 at (1,0)).
  void operator()(const Quad& q) const {
    gpu::GpuPrimitive first = makeTriangle(q.v0, q.v1, q.v2);
    gpu::GpuPrimitive second = makeTriangle(q.v0, q.v2, q.v3);
    if (material.diffuseTexture >= 0) {
      uint32_t base = addVertices({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
      attachVertices(first, {base, base + 1, base + 2}, false);
      attachVertices(second, {base, base + 2, base + 3}, false);
    }
    flat.primitives.push_back(first);
    flat.primitives.push_back(second);
  }
  void operator()(const Cylinder& c) const {
    gpu::GpuPrimitive prim{};
    prim.kind = RT_PRIM_CYLINDER;
    prim.a = glm::vec4(c.center, c.radius);
    prim.b = glm::vec4(c.axis, c.halfHeight);
    flat.primitives.push_back(prim);
  }
  void operator()(const MeshInstance& instance) const {
    const TriangleMesh& mesh = scene.meshes.at(instance.mesh);
    std::vector<glm::vec3> world;
    world.reserve(mesh.positions.size());
    for (const glm::vec3& p : mesh.positions) {
      world.push_back(glm::vec3(instance.objectToWorld * glm::vec4(p, 1.0f)));
    }
    bool smooth = !mesh.normals.empty();
    bool needsVertices = smooth || !mesh.uvs.empty() || material.diffuseTexture >= 0;
    uint32_t base = needsVertices ? addMeshVertices(mesh, instance, world) : 0;
    for (const glm::uvec3& face : mesh.faces) {
      gpu::GpuPrimitive prim = makeTriangle(world[face.x], world[face.y], world[face.z]);
      if (needsVertices) attachVertices(prim, glm::uvec3(base) + face, smooth);
      flat.primitives.push_back(prim);
    }
  }

 private:
  uint32_t addVertices(std::initializer_list<glm::vec2> uvs) const {
    uint32_t base = static_cast<uint32_t>(flat.vertices.size());
    for (const glm::vec2& uv : uvs) flat.vertices.push_back({glm::vec3(0.0f), uv.x, uv.y});
    return base;
  }

  uint32_t addMeshVertices(const TriangleMesh& mesh, const MeshInstance& instance,
                           const std::vector<glm::vec3>& world) const {
    uint32_t base = static_cast<uint32_t>(flat.vertices.size());
    // Normals transform with the inverse transpose (non-uniform scale, mirroring).
    glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(instance.objectToWorld)));
    Aabb bounds;
    for (const glm::vec3& p : world) bounds.grow(p);
    for (size_t i = 0; i < world.size(); ++i) {
      gpu::GpuVertex vertex{};
      if (!mesh.normals.empty()) vertex.normal = glm::normalize(normalMatrix * mesh.normals[i]);
      glm::vec2 uv = mesh.uvs.empty() ? projectedUv(world[i], bounds.center(), uvPole) : mesh.uvs[i];
      vertex.u = uv.x;
      vertex.v = uv.y;
      flat.vertices.push_back(vertex);
    }
    return base;
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
    box.grow(glm::vec3(prim.b));
    box.grow(glm::vec3(prim.c));
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

void collectPrimitives(const Scene& scene, FlatScene& flat) {
  for (uint32_t shapeIndex = 0; shapeIndex < scene.shapes.size(); ++shapeIndex) {
    const Shape& shape = scene.shapes[shapeIndex];
    size_t first = flat.primitives.size();
    PrimitiveSink sink{scene, scene.materials.at(shape.material), flat.info.sphereUvPole, flat};
    std::visit(sink, shape.geometry);
    for (size_t i = first; i < flat.primitives.size(); ++i) {
      flat.primitives[i].materialIndex = shape.material;
      flat.primitives[i].shapeIndex = shapeIndex;
    }
  }
}

// Camera-relative coordinates (before the BVH is built): floats are coarse
// far from the world origin (ulp 0.0625 at 1e6), so a scene far from it is
// moved next to the camera, where what the camera sees is resolved finely.
// Each coordinate is one float subtraction, rounded once; a scene that is
// only translated gives the GPU the very same numbers.
void recenterOnCamera(FlatScene& flat) {
  glm::vec3 origin = flat.info.cameraPosition;
  for (gpu::GpuPrimitive& prim : flat.primitives) {
    prim.a = glm::vec4(glm::vec3(prim.a) - origin, prim.a.w);
    if (prim.kind != RT_PRIM_TRIANGLE) continue;
    prim.b = glm::vec4(glm::vec3(prim.b) - origin, prim.b.w);
    prim.c = glm::vec4(glm::vec3(prim.c) - origin, prim.c.w);
  }
  for (gpu::GpuPointLight& light : flat.pointLights) light.position -= origin;
  flat.info.cameraPosition = glm::vec3(0.0f);
  flat.frameOrigin = origin;
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
  gpu::GpuMaterial out{};
  bool replacedByTexture = m.diffuseTexture >= 0 && !m.textureTintedByColor;
  out.diffuseColor = replacedByTexture ? glm::vec3(1.0f) : m.diffuseColor;
  out.kd = m.kd;
  out.specularColor = m.specularColor;
  out.ks = m.ks;
  out.specularExponent = m.specularExponent;
  out.reflectivity = m.reflectivity;
  out.transmission = m.transmission;
  out.ior = m.ior;
  out.diffuseTexture = m.diffuseTexture;
  return out;
}

void addTextures(const Scene& scene, FlatScene& flat) {
  for (const Texture& texture : scene.textures) {
    const ImageRgba8& image = texture.image;
    flat.textureInfos.push_back(
        {static_cast<uint32_t>(flat.texels.size()), image.width, image.height, 0});
    for (size_t i = 0; i + 3 < image.rgba.size(); i += 4) {
      flat.texels.push_back(uint32_t(image.rgba[i]) | uint32_t(image.rgba[i + 1]) << 8 |
                            uint32_t(image.rgba[i + 2]) << 16 | uint32_t(image.rgba[i + 3]) << 24);
    }
  }
}

// The world axis closest to the camera's up vector: sphere textures stand
// upright in the image (z for the Path-of-Light files, y for the others).
uint32_t dominantAxis(const glm::vec3& v) {
  glm::vec3 a = glm::abs(v);
  return a.x >= a.y && a.x >= a.z ? 0u : (a.y >= a.z ? 1u : 2u);
}

}  // namespace

void fillCamera(const Camera& camera, uint32_t width, uint32_t height, gpu::GpuSceneInfo& info,
                const glm::vec3& frameOrigin) {
  glm::vec3 forward = glm::normalize(camera.forward);
  glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
  info.cameraPosition = camera.position - frameOrigin;
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
  for (const Material& m : scene.materials) flat.materials.push_back(toGpu(m));
  addTextures(scene, flat);
  for (const PointLight& light : scene.pointLights) {
    flat.pointLights.push_back(
        {light.position, 0.0f, light.diffuseIntensity, 0.0f, light.specularIntensity, 0.0f});
  }
  flat.info.sphereUvPole = dominantAxis(scene.camera.up);
  collectPrimitives(scene, flat);
  recenterOnCamera(flat);
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
  info.textureCount = static_cast<uint32_t>(flat.textureInfos.size());
  info.shadingModel =
      conventions.shading == ShadingModel::Coursework ? RT_SHADING_COURSEWORK : RT_SHADING_STANDARD;
  return flat;
}

}  // namespace rt
