#include "encode/FlatScene.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_access.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>
#include <initializer_list>
#include <optional>
#include <variant>

#include "bvh/Bvh.hpp"
#include "encode/AreaLights.hpp"
#include "encode/Conventions.hpp"
#include "encode/GpuBvh.hpp"
#include "scene/SceneBounds.hpp"
#include "util/Error.hpp"

namespace rt {
namespace {

// The colour of hit pixels in `rendermode: binary` (misses show the background).
constexpr glm::vec3 kBinaryHitColor{1.0f, 0.0f, 0.0f};

// The one corner layout of every triangle record, GpuPrimitive (a, b, c)
// and mesh GpuItem rows alike: the corners themselves (watertight
// intersection needs the shared floats), each with its GpuVertex index as
// float bits in w.
gpu::GpuItem triangleRows(const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2,
                          glm::uvec3 vertices = glm::uvec3(0)) {
  return {glm::vec4(v0, glm::uintBitsToFloat(vertices.x)),
          glm::vec4(v1, glm::uintBitsToFloat(vertices.y)),
          glm::vec4(v2, glm::uintBitsToFloat(vertices.z))};
}

void setTriangleRows(gpu::GpuPrimitive& prim, const gpu::GpuItem& rows) {
  prim.a = rows.row0;
  prim.b = rows.row1;
  prim.c = rows.row2;
}

gpu::GpuPrimitive makeTriangle(const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2) {
  gpu::GpuPrimitive prim{};
  prim.kind = RT_PRIM_TRIANGLE;
  setTriangleRows(prim, triangleRows(v0, v1, v2));
  return prim;
}

// A vertex record; white leaves the diffuse colour as it is.
gpu::GpuVertex vertexRecord(const glm::vec3& normal, const glm::vec2& uv,
                            const glm::vec3& color = glm::vec3(1.0f)) {
  return {normal, uv.x, color, uv.y};
}

// Points a triangle at three GpuVertex records.
void attachVertices(gpu::GpuPrimitive& prim, glm::uvec3 indices, bool smooth) {
  setTriangleRows(prim,
                  triangleRows(glm::vec3(prim.a), glm::vec3(prim.b), glm::vec3(prim.c), indices));
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

// A mesh placed by a shape, waiting for the mesh's BVH (built once per mesh).
struct PendingInstance {
  uint32_t primitive;  // index of its GpuPrimitive (kind RT_PRIM_INSTANCE)
  uint32_t mesh;
  glm::mat4 objectToFrame;  // object space to GPU coordinates
};

// Turns shapes into GPU primitives, and adds vertex records where a
// triangle needs more than its corners: smooth normals or texture coordinates.
struct PrimitiveSink {
  const gpu::GpuMaterial& material;
  FlatScene& flat;
  std::vector<PendingInstance>& instances;

  glm::vec3 at(const WorldPoint& p) const { return flat.frame.point(p); }

  void operator()(const Sphere& s) const {
    gpu::GpuPrimitive prim{};
    prim.kind = RT_PRIM_SPHERE;
    prim.a = glm::vec4(at(s.center), s.radius);
    flat.primitives.push_back(prim);
  }
  // A lone triangle's UVs are its barycentric coordinates: (0,0), (1,0), (0,1).
  void operator()(const Triangle& t) const {
    flat.primitives.push_back(makeTriangle(at(t.v0), at(t.v1), at(t.v2)));
  }
  // Quads map the unit square onto v0 v1 v2 v3 (v0 at uv (0,0), v1 at (1,0)).
  void operator()(const Quad& q) const {
    gpu::GpuPrimitive first = makeTriangle(at(q.v0), at(q.v1), at(q.v2));
    gpu::GpuPrimitive second = makeTriangle(at(q.v0), at(q.v2), at(q.v3));
    if (samplesTextures(material)) {
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
    prim.a = glm::vec4(at(c.center), c.radius);
    prim.b = glm::vec4(c.axis, c.halfHeight);
    flat.primitives.push_back(prim);
  }
  void operator()(const MeshInstance& instance) const {
    gpu::GpuPrimitive prim{};
    prim.kind = RT_PRIM_INSTANCE;
    instances.push_back({static_cast<uint32_t>(flat.primitives.size()), instance.mesh,
                         flat.frame.transform(instance.objectToWorld)});
    flat.primitives.push_back(prim);
  }

 private:
  uint32_t addVertices(std::initializer_list<glm::vec2> uvs) const {
    uint32_t base = static_cast<uint32_t>(flat.vertices.size());
    for (const glm::vec2& uv : uvs) flat.vertices.push_back(vertexRecord(glm::vec3(0.0f), uv));
    return base;
  }
};

Aabb transformedBounds(const Aabb& box, const glm::mat4& transform) {
  Aabb out;
  if (box.empty()) return out;
  for (int corner = 0; corner < 8; ++corner) {
    glm::vec3 p((corner & 1) ? box.max.x : box.min.x, (corner & 2) ? box.max.y : box.min.y,
                (corner & 4) ? box.max.z : box.min.z);
    out.grow(glm::vec3(transform * glm::vec4(p, 1.0f)));
  }
  return out;
}

// One mesh on the GPU: its triangles (in BVH order) and binary BVH, laid out
// after the top level once that is known.
struct MeshBlas {
  Bvh bvh;
  std::vector<gpu::GpuItem> triangles;
  uint32_t flags = 0;  // RT_PRIM_HAS_VERTICES / RT_PRIM_SMOOTH for its instances
  Aabb bounds;
  bool baked = false;      // built in world space (its one instance's placement applied)
  uint32_t root = 0;       // GPU node index, once laid out
  uint32_t firstItem = 0;  // its first triangle in FlatScene::items, once laid out
};

Bvh buildTree(const std::vector<Aabb>& boxes, uint32_t leafSize, const FlattenOptions& options) {
  if (options.accel == AccelKind::None) {
    Aabb all;
    for (const Aabb& box : boxes) all.grow(box);
    return bruteForceTree(static_cast<uint32_t>(boxes.size()), leafSize, all);
  }
  BvhBuildOptions build;
  build.maxDepth = RT_BVH_MAX_DEPTH;
  build.maxLeafSize = leafSize;
  build.threads = options.buildThreads;
  return buildBvh(boxes, build);
}

class MeshEncoder {
 public:
  MeshEncoder(const Scene& scene, FlatScene& flat, const FlattenOptions& options)
      : scene_(scene), flat_(flat), options_(options) {}

  // `placement` is applied to the vertices: a mesh used by one shape is
  // stored in world space (tight top-level box, nothing to transform at
  // shading); a shared mesh once, in object space (identity).
  MeshBlas build(uint32_t meshIndex, const glm::mat4& placement, bool textured) {
    const TriangleMesh& mesh = scene_.meshes.at(meshIndex);
    MeshBlas blas;
    std::vector<glm::vec3> points;
    points.reserve(mesh.positions.size());
    for (const glm::vec3& p : mesh.positions)
      points.push_back(glm::vec3(placement * glm::vec4(p, 1.0f)));
    // A mirroring placement reverses the winding; swapping two corners keeps
    // the winding normal outward, as the normal matrix does for instances.
    bool mirrored = glm::determinant(glm::mat3(placement)) < 0.0f;
    bool needsVertices =
        !mesh.normals.empty() || !mesh.uvs.empty() || !mesh.colors.empty() || textured;
    uint32_t base = needsVertices ? addMeshVertices(mesh, placement, points) : 0;
    blas.flags =
        (needsVertices ? RT_PRIM_HAS_VERTICES : 0u) | (!mesh.normals.empty() ? RT_PRIM_SMOOTH : 0u);
    std::vector<gpu::GpuItem> triangles;
    std::vector<Aabb> boxes;
    triangles.reserve(mesh.faces.size());
    boxes.reserve(mesh.faces.size());
    for (glm::uvec3 face : mesh.faces) {
      if (mirrored) std::swap(face.y, face.z);
      glm::vec3 v0 = points[face.x];
      glm::vec3 v1 = points[face.y];
      glm::vec3 v2 = points[face.z];
      glm::uvec3 corners = needsVertices ? glm::uvec3(base) + face : glm::uvec3(0);
      triangles.push_back(triangleRows(v0, v1, v2, corners));
      Aabb box;
      box.grow(v0);
      box.grow(v1);
      box.grow(v2);
      boxes.push_back(box);
      blas.bounds.grow(box);
    }
    blas.bvh = buildTree(boxes, options_.maxLeafSize, options_);
    blas.triangles.reserve(triangles.size());
    for (uint32_t index : blas.bvh.primitiveOrder) blas.triangles.push_back(triangles[index]);
    return blas;
  }

 private:
  uint32_t addMeshVertices(const TriangleMesh& mesh, const glm::mat4& placement,
                           const std::vector<glm::vec3>& points) {
    uint32_t base = static_cast<uint32_t>(flat_.vertices.size());
    // Normals transform with the inverse transpose (non-uniform scale, mirroring).
    glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(placement)));
    Aabb bounds;
    for (const glm::vec3& p : points) bounds.grow(p);
    for (size_t i = 0; i < points.size(); ++i) {
      glm::vec3 normal =
          mesh.normals.empty() ? glm::vec3(0.0f) : glm::normalize(normalMatrix * mesh.normals[i]);
      glm::vec2 uv = mesh.uvs.empty()
                         ? projectedUv(points[i], bounds.center(), flat_.info.sphereUvPole)
                         : mesh.uvs[i];
      glm::vec3 color = mesh.colors.empty() ? glm::vec3(1.0f) : mesh.colors[i];
      flat_.vertices.push_back(vertexRecord(normal, uv, color));
    }
    return base;
  }

  const Scene& scene_;
  FlatScene& flat_;
  const FlattenOptions& options_;
};

// Turns shapes into primitives, mesh instances first: their item indices
// then number the instance root nodes (see GpuBvhNode).
// `shapeMaterials` gives each shape's GPU material (light shapes have their own).
std::vector<PendingInstance> collectPrimitives(const Scene& scene,
                                               const std::vector<uint32_t>& shapeMaterials,
                                               FlatScene& flat) {
  std::vector<PendingInstance> instances;
  for (uint32_t shapeIndex = 0; shapeIndex < scene.shapes.size(); ++shapeIndex) {
    const Shape& shape = scene.shapes[shapeIndex];
    size_t first = flat.primitives.size();
    const gpu::GpuMaterial& material = flat.materials.at(shapeMaterials[shapeIndex]);
    std::visit(PrimitiveSink{material, flat, instances}, shape.geometry);
    for (size_t i = first; i < flat.primitives.size(); ++i) {
      flat.primitives[i].materialIndex = shapeMaterials[shapeIndex];
      flat.primitives[i].shapeIndex = shapeIndex;
    }
  }
  std::vector<gpu::GpuPrimitive> ordered;
  ordered.reserve(flat.primitives.size());
  for (PendingInstance& instance : instances) {
    ordered.push_back(flat.primitives[instance.primitive]);
    instance.primitive = static_cast<uint32_t>(ordered.size() - 1);
  }
  for (const gpu::GpuPrimitive& prim : flat.primitives) {
    if (prim.kind != RT_PRIM_INSTANCE) ordered.push_back(prim);
  }
  flat.primitives = std::move(ordered);
  return instances;
}

// Builds each used mesh's triangles and BVH once, and fills its instances'
// primitives (world-to-object rows, flags). Returns the BVHs by mesh.
std::vector<std::optional<MeshBlas>> addMeshes(const Scene& scene,
                                               const std::vector<PendingInstance>& instances,
                                               const FlattenOptions& options, FlatScene& flat) {
  std::vector<uint32_t> uses(scene.meshes.size(), 0);
  std::vector<bool> textured(scene.meshes.size(), false);
  for (const PendingInstance& instance : instances) {
    uses.at(instance.mesh)++;
    const gpu::GpuPrimitive& prim = flat.primitives[instance.primitive];
    // The GPU material: an area light's shape has its own copy, past the scene's.
    textured[instance.mesh] =
        textured[instance.mesh] || samplesTextures(flat.materials.at(prim.materialIndex));
  }
  MeshEncoder builder(scene, flat, options);
  std::vector<std::optional<MeshBlas>> meshes(scene.meshes.size());
  for (const PendingInstance& instance : instances) {
    std::optional<MeshBlas>& blas = meshes[instance.mesh];
    bool bake = uses[instance.mesh] == 1;
    if (!blas) {
      blas = builder.build(instance.mesh, bake ? instance.objectToFrame : glm::mat4(1.0f),
                           textured[instance.mesh]);
      blas->baked = bake;
    }
    glm::mat4 worldToObject = bake ? glm::mat4(1.0f) : glm::inverse(instance.objectToFrame);
    gpu::GpuPrimitive& prim = flat.primitives[instance.primitive];
    // glm is column-major: row r of the matrix is (m[0][r], m[1][r], m[2][r], m[3][r]).
    glm::vec4* rows[3] = {&prim.a, &prim.b, &prim.c};
    for (int r = 0; r < 3; ++r) *rows[r] = glm::row(worldToObject, r);
    prim.flags =
        blas->flags |
        (hasAlphaCutout(flat.materials.at(prim.materialIndex)) ? RT_PRIM_ALPHA_CUTOUT : 0u);
  }
  return meshes;
}

Aabb instanceBounds(const gpu::GpuPrimitive& prim, const MeshBlas& blas) {
  glm::mat4 worldToObject(1.0f);
  worldToObject = glm::row(worldToObject, 0, prim.a);
  worldToObject = glm::row(worldToObject, 1, prim.b);
  worldToObject = glm::row(worldToObject, 2, prim.c);
  return transformedBounds(blas.bounds, glm::inverse(worldToObject));
}

// Nodes: the top-level root (node 0), one copy of the mesh root per instance,
// the rest of the top level, then each mesh's tree. Items: every top-level primitive's rows, then
// each mesh's triangles.
void addBvh(const std::vector<PendingInstance>& instances,
            std::vector<std::optional<MeshBlas>>& meshes, const FlattenOptions& options,
            FlatScene& flat) {
  std::vector<Aabb> bounds(flat.primitives.size());
  for (size_t i = 0; i < flat.primitives.size(); ++i) {
    if (flat.primitives[i].kind != RT_PRIM_INSTANCE)
      bounds[i] = primitiveBounds(flat.primitives[i]);
  }
  for (const PendingInstance& instance : instances) {
    bounds[instance.primitive] =
        instanceBounds(flat.primitives[instance.primitive], *meshes[instance.mesh]);
  }
  for (const gpu::GpuPrimitive& prim : flat.primitives)
    flat.items.push_back({prim.a, prim.b, prim.c});

  Bvh top = buildTree(bounds, 1, options);
  appendBvhNodes(
      top,
      [&](uint32_t first, uint32_t) {
        uint32_t item = top.primitiveOrder[first];
        return topLevelLeaf(item, flat.primitives[item].kind);
      },
      flat.bvhNodes);
  // Room for the instance root copies at nodes 1..I (see GpuBvhNode): the
  // top level's own nodes move up by I.
  uint32_t shift = static_cast<uint32_t>(instances.size());
  for (gpu::GpuBvhNode& node : flat.bvhNodes) {
    for (uint32_t* ref : {&node.leftRef, &node.rightRef}) {
      if ((*ref & RT_REF_LEAF) == 0) *ref += shift;
    }
  }
  flat.bvhNodes.insert(flat.bvhNodes.begin() + 1, shift, gpu::GpuBvhNode{});
  uint32_t meshDepth = 0;
  for (std::optional<MeshBlas>& blas : meshes) {
    if (!blas) continue;
    uint32_t firstTriangle = static_cast<uint32_t>(flat.items.size());
    blas->firstItem = firstTriangle;
    flat.items.insert(flat.items.end(), blas->triangles.begin(), blas->triangles.end());
    blas->root = appendBvhNodes(
        blas->bvh,
        [&](uint32_t first, uint32_t count) { return meshLeaf(firstTriangle + first, count); },
        flat.bvhNodes);
    meshDepth = std::max(meshDepth, blas->bvh.depth);
  }
  std::vector<uint32_t> flatMeshOf(meshes.size(), 0);
  for (size_t mesh = 0; mesh < meshes.size(); ++mesh) {
    if (!meshes[mesh]) continue;
    flatMeshOf[mesh] = static_cast<uint32_t>(flat.meshes.size());
    flat.meshes.push_back(
        {meshes[mesh]->firstItem, static_cast<uint32_t>(meshes[mesh]->triangles.size())});
  }
  for (const PendingInstance& instance : instances) {
    const MeshBlas& blas = *meshes[instance.mesh];
    flat.bvhNodes[1 + instance.primitive] = flat.bvhNodes[blas.root];
    flat.instances.push_back({instance.primitive, flatMeshOf[instance.mesh],
                              blas.baked ? glm::mat4(1.0f) : instance.objectToFrame});
  }
  flat.bvhDepth = top.depth + meshDepth;
  // A lone baked instance: walks start at its root copy (GpuSceneInfo).
  bool loneInstance = flat.primitives.size() == 1 && instances.size() == 1;
  flat.info.soleInstance = loneInstance ? instances[0].primitive : RT_NO_INSTANCE;
}

uint32_t wrapOf(TextureSampling::Wrap wrap) {
  switch (wrap) {
    case TextureSampling::Wrap::Clamp: return RT_WRAP_CLAMP;
    case TextureSampling::Wrap::Mirror: return RT_WRAP_MIRROR;
    case TextureSampling::Wrap::Repeat: break;
  }
  return RT_WRAP_REPEAT;
}

uint32_t textureFlags(const Texture& texture) {
  return (texture.linear ? RT_TEXTURE_LINEAR : 0u) |
         (texture.sampling.nearest ? RT_TEXTURE_NEAREST : 0u) |
         wrapOf(texture.sampling.wrapU) << RT_TEXTURE_WRAP_U_SHIFT |
         wrapOf(texture.sampling.wrapV) << RT_TEXTURE_WRAP_V_SHIFT;
}

uint32_t alphaModeOf(const Material& m) {
  switch (m.alphaMode) {
    case Material::Alpha::Mask: return RT_ALPHA_MASK;
    case Material::Alpha::Blend: return RT_ALPHA_BLEND;
    case Material::Alpha::Opaque: break;
  }
  return RT_ALPHA_OPAQUE;
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
  out.normalTexture = m.normalTexture;
  out.normalScale = m.normalScale;
  out.emission = glm::vec3(0.0f);
  out.emissionProfile = RT_EMISSION_ISOTROPIC;
  out.emissionTexture = m.glowTexture;
  out.metalRoughTexture = m.metalRoughTexture;
  out.metallic = m.metallic;
  out.roughness = m.roughness;
  out.flags = (m.tintedMirror ? RT_MATERIAL_TINTED_MIRROR : 0u) |
              (m.tintedTransmission ? RT_MATERIAL_TINTED_TRANSMISSION : 0u) |
              (m.thinWalled ? RT_MATERIAL_THIN_WALLED : 0u);
  out.transmissionTexture = m.transmissionTexture;
  out.alphaTexture = m.alphaTexture;
  out.alphaMode = alphaModeOf(m);
  out.alphaFactor = m.alphaFactor;
  out.alphaCutoff = m.alphaCutoff;
  if (m.glows()) {
    out.emission = m.glow;
    out.emissionProfile = m.glowTimesVertexColors ? RT_EMISSION_UNLIT : RT_EMISSION_GLOW;
  }
  return out;
}

// Each shape's GPU material. An area light's shape gets a copy of its
// material that emits, so that no other shape sharing the material glows.
std::vector<uint32_t> addLightMaterials(const Scene& scene, const FlatAreaLights& lights,
                                        FlatScene& flat) {
  std::vector<uint32_t> shapeMaterials;
  for (const Shape& shape : scene.shapes) shapeMaterials.push_back(shape.material);
  for (size_t i = 0; i < scene.areaLights.size(); ++i) {
    uint32_t shape = scene.areaLights[i].shape;
    gpu::GpuMaterial material = flat.materials.at(shapeMaterials[shape]);
    material.emission = lights.emission[i];
    material.emissionTexture = -1;  // a light, not a glow
    material.emissionProfile = flat.areaLights.at(i).profile;
    flat.materials.push_back(material);
    shapeMaterials[shape] = static_cast<uint32_t>(flat.materials.size() - 1);
  }
  return shapeMaterials;
}

uint32_t gpuRenderMode(RenderMode mode) {
  switch (mode) {
    case RenderMode::Binary: return RT_MODE_BINARY;
    case RenderMode::Phong: return RT_MODE_PHONG;
    case RenderMode::PathTracer: return RT_MODE_PATH_TRACER;
  }
  return RT_MODE_PHONG;
}

void addTextures(const Scene& scene, FlatScene& flat) {
  for (const Texture& texture : scene.textures) {
    const ImageRgba8& image = texture.image;
    flat.textureInfos.push_back({static_cast<uint32_t>(flat.texels.size()), image.width,
                                 image.height, textureFlags(texture)});
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

bool samplesTextures(const gpu::GpuMaterial& material) {
  return material.diffuseTexture >= 0 || material.normalTexture >= 0 ||
         material.emissionTexture >= 0 || material.metalRoughTexture >= 0 ||
         material.transmissionTexture >= 0 ||
         (hasAlphaCutout(material) && material.alphaTexture >= 0);
}

bool hasAlphaCutout(const gpu::GpuMaterial& material) {
  return material.alphaMode != RT_ALPHA_OPAQUE;
}

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

void fillCamera(const Camera& camera, uint32_t width, uint32_t height, const GpuFrame& frame,
                gpu::GpuSceneInfo& info) {
  CameraBasis basis = cameraBasis(camera);
  info.cameraPosition = frame.point(camera.position);
  info.cameraForward = basis.forward;
  info.cameraRight = basis.right;
  info.cameraUp = basis.up;
  info.tanHalfFovY = std::tan(glm::radians(camera.fovYDegrees) * 0.5f);
  info.aspect = static_cast<float>(width) / static_cast<float>(height);
  info.apertureRadius = camera.type == CameraType::ThinLens ? camera.apertureRadius : 0.0f;
  info.focusDistance = camera.focusDistance;
  info.width = width;
  info.height = height;
}

namespace {

// The steepest slope of the display mapping (exposure, then sRGB's 12.92
// near black): the bailout is in steps of the written image, so a dropped
// branch or light sample moves an sRGB pixel as little as a linear one.
float displaySlope(const ToneMapping& mapping) {
  return std::max(mapping.exposure, 1e-6f) * (mapping.srgbEncode ? 12.92f : 1.0f);
}

// A scene that nothing lights renders black whatever it holds (a student's
// path-traced box whose lamp lived outside the file): said, so that the
// black image is not taken for a fault of the renderer.
bool nothingLights(const Scene& scene, const LightingConventions& conventions,
                   const FlatScene& flat) {
  const glm::vec3 zero(0.0f);
  return scene.settings.mode != RenderMode::Binary && flat.pointLights.empty() &&
         flat.areaLights.empty() && flat.emitters.empty() && scene.backgroundColor == zero &&
         conventions.ambient == zero;
}

}  // namespace

FlatScene flattenScene(const Scene& scene, const FlattenOptions& options) {
  if (const std::optional<std::string> problem = precisionProblem(scene)) {
    throw Error((scene.sourcePath.empty() ? "scene" : scene.sourcePath.string()) + ": " + *problem);
  }
  FlatScene flat;
  flat.accel = options.accel;
  uint32_t width = options.width ? options.width : scene.camera.width;
  uint32_t height = options.height ? options.height : scene.camera.height;
  // Camera-relative coordinates: floats are coarse far from the world origin
  // (ulp 0.0625 at 1e6), so the scene is moved next to the camera, where
  // what the camera sees is resolved finely, before anything is rounded.
  flat.frame.origin = options.frameOrigin.value_or(scene.camera.position);
  fillCamera(scene.camera, width, height, flat.frame, flat.info);
  for (const Material& m : scene.materials) flat.materials.push_back(toGpu(m));
  addTextures(scene, flat);
  for (const PointLight& light : scene.pointLights) {
    flat.pointLights.push_back({flat.frame.point(light.position), 0.0f, light.diffuseIntensity,
                                0.0f, light.specularIntensity, 0.0f});
  }
  flat.info.sphereUvPole = dominantAxis(scene.camera.up);
  LightingConventions conventions = lightingConventionsFor(scene, options.shading);
  if (scene.settings.mode == RenderMode::PathTracer &&
      options.shading == ShadingModel::Coursework) {
    flat.warnings.push_back("the path tracer uses the standard shading model");
  }
  FlatAreaLights areaLights = flattenAreaLights(scene, flat.frame, conventions.lightScale);
  flat.areaLights = std::move(areaLights.lights);
  flat.emitters = std::move(areaLights.emitters);
  std::vector<uint32_t> shapeMaterials = addLightMaterials(scene, areaLights, flat);
  if (nothingLights(scene, conventions, flat)) {
    flat.warnings.push_back(
        "nothing lights the scene (no light sources, no glowing shapes, a black background, no "
        "ambient light): the image is black");
  }
  std::vector<PendingInstance> instances = collectPrimitives(scene, shapeMaterials, flat);
  std::vector<std::optional<MeshBlas>> meshes = addMeshes(scene, instances, options, flat);
  addBvh(instances, meshes, options, flat);

  gpu::GpuSceneInfo& info = flat.info;
  info.backgroundColor = scene.backgroundColor;
  info.maxBounces = scene.settings.maxBounces;
  info.distributedBounces =
      scene.settings.mode == RenderMode::Phong ? scene.settings.distributedBounces : 0u;
  // Off is no limit at all: the shader clamps without a branch.
  info.indirectClamp =
      scene.settings.indirectClamp > 0.0f ? scene.settings.indirectClamp : RT_FAR_VALUE;
  info.branchBailout =
      scene.settings.mode == RenderMode::PathTracer
          ? RT_MIN_BRANCH_WEIGHT
          : std::max(scene.settings.branchBailout /
                         displaySlope(options.displayMapping.value_or(toneMappingFor(scene))),
                     RT_MIN_BRANCH_WEIGHT);
  info.binaryHitColor = kBinaryHitColor;
  info.renderMode = gpuRenderMode(scene.settings.mode);
  info.pointLightCount = static_cast<uint32_t>(flat.pointLights.size());
  info.areaLightCount = static_cast<uint32_t>(flat.areaLights.size());
  info.areaLightSamples = 0;
  for (const gpu::GpuAreaLight& light : flat.areaLights) info.areaLightSamples += light.samples;
  info.primitiveCount = static_cast<uint32_t>(flat.primitives.size());
  info.bvhNodeCount = static_cast<uint32_t>(flat.bvhNodes.size());
  info.lightFalloff = conventions.falloff;
  info.lightScale = conventions.lightScale;
  info.textureCount = static_cast<uint32_t>(flat.textureInfos.size());
  info.shadingModel =
      conventions.shading == ShadingModel::Coursework ? RT_SHADING_COURSEWORK : RT_SHADING_STANDARD;
  info.ambient = conventions.ambient;
  info.mirrorsReplaceLocalLight = conventions.mirrorsReplaceLocalLight ? 1u : 0u;
  return flat;
}

}  // namespace rt
