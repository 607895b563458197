#include "formats/gltf/GltfMesh.hpp"

#include <cmath>

#include "formats/common/UnitVector.hpp"
#include "formats/common/VertexColors.hpp"
#include "formats/gltf/GltfAccessor.hpp"

namespace rt::gltf {
namespace {

struct PrimitiveRef {
  const tinygltf::Primitive& primitive;
  std::string where;  // "meshes[m].primitives[p]"
};

int attribute(const tinygltf::Primitive& primitive, const std::string& name) {
  auto found = primitive.attributes.find(name);
  return found == primitive.attributes.end() ? -1 : found->second;
}

bool isFinite(glm::vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

template <typename Vec>
std::vector<Vec> toVectors(const std::vector<float>& values) {
  constexpr size_t n = sizeof(Vec) / sizeof(float);
  std::vector<Vec> out(values.size() / n);
  for (size_t i = 0; i < out.size(); ++i) {
    for (size_t c = 0; c < n; ++c) out[i][int(c)] = values[i * n + c];
  }
  return out;
}

// Reads a vertex attribute that must have exactly one element per vertex.
std::vector<float> readAttribute(Context& context, const PrimitiveRef& ref, const std::string& name,
                                 AccessorUse use, size_t vertexCount) {
  int accessor = attribute(ref.primitive, name);
  std::string where = ref.where + ".attributes." + name;
  size_t count = accessorCount(context, accessor, where);
  if (count != vertexCount) {
    context.fail(where, "accessor " + std::to_string(accessor) + " has " + std::to_string(count) +
                            " elements, POSITION has " + std::to_string(vertexCount));
  }
  return readFloats(context, accessor, use, where);
}

std::vector<glm::vec3> readPositions(Context& context, const PrimitiveRef& ref) {
  int accessor = attribute(ref.primitive, "POSITION");
  if (accessor < 0) context.fail(ref.where + ".attributes", "POSITION is missing");
  std::string where = ref.where + ".attributes.POSITION";
  std::vector<glm::vec3> positions =
      toVectors<glm::vec3>(readFloats(context, accessor, AccessorUse::Vec3, where));
  for (size_t i = 0; i < positions.size(); ++i) {
    if (!isFinite(positions[i])) {
      context.fail(where, "vertex " + std::to_string(i) + " is not finite");
    }
  }
  return positions;
}

// Unit normals, or none (the renderer then uses face normals) when the file's
// are unusable: zero, or not finite.
std::vector<glm::vec3> readNormals(Context& context, const PrimitiveRef& ref, size_t vertexCount) {
  if (attribute(ref.primitive, "NORMAL") < 0) return {};
  std::vector<glm::vec3> normals =
      toVectors<glm::vec3>(readAttribute(context, ref, "NORMAL", AccessorUse::Vec3, vertexCount));
  size_t bad = 0;
  for (glm::vec3& n : normals) {
    if (!normalizeInPlace(n)) ++bad;
  }
  if (bad == 0) return normals;
  context.warn(ref.where + ".attributes.NORMAL",
               std::to_string(bad) + " normals are zero or not finite; using face normals");
  return {};
}

std::vector<glm::vec2> readUvs(Context& context, const PrimitiveRef& ref, size_t vertexCount,
                               const UvMapping& mapping) {
  std::string name = "TEXCOORD_" + std::to_string(mapping.set);
  if (attribute(ref.primitive, name) < 0) return {};
  std::vector<glm::vec2> uvs =
      toVectors<glm::vec2>(readAttribute(context, ref, name, AccessorUse::Vec2, vertexCount));
  for (glm::vec2& uv : uvs) {
    uv = glm::vec2(mapping.transform * glm::vec3(uv, 1.0f));
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) {
      context.warn(ref.where + ".attributes." + name,
                   "texture coordinates are not finite; dropped");
      return {};
    }
  }
  return uvs;
}

// COLOR_0: linear RGB (VEC3) or RGBA (VEC4), which the base colour is
// multiplied by (glTF 2.0, 3.9.2). Alpha is not used: nothing is blended.
std::vector<glm::vec3> readColors(Context& context, const PrimitiveRef& ref, size_t vertexCount) {
  int accessor = attribute(ref.primitive, "COLOR_0");
  if (accessor < 0) return {};
  const auto& accessors = context.model().accessors;
  bool rgba =
      size_t(accessor) < accessors.size() && accessors[size_t(accessor)].type == TINYGLTF_TYPE_VEC4;
  std::vector<float> values = readAttribute(
      context, ref, "COLOR_0", rgba ? AccessorUse::Vec4 : AccessorUse::Vec3, vertexCount);
  size_t stride = rgba ? 4 : 3;
  std::vector<glm::vec3> colors(values.size() / stride);
  for (size_t i = 0; i < colors.size(); ++i) {
    colors[i] = clampedColor({values[i * stride], values[i * stride + 1], values[i * stride + 2]});
  }
  return colors;
}

void noteIgnoredAttributes(Context& context, const PrimitiveRef& ref) {
  if (!ref.primitive.targets.empty()) context.ignored("morph targets", ref.where);
}

// The vertex indices in drawing order: the index accessor, or 0..n-1.
struct IndexSource {
  std::vector<uint32_t> indices;
  size_t count = 0;
  bool indexed = false;
  uint32_t operator[](size_t i) const { return indexed ? indices[i] : uint32_t(i); }
};

IndexSource readIndexSource(Context& context, const PrimitiveRef& ref, size_t vertexCount) {
  IndexSource source;
  if (ref.primitive.indices < 0) {
    source.count = vertexCount;
    return source;
  }
  std::string where = ref.where + ".indices";
  source.indices = readIndices(context, ref.primitive.indices, where);
  source.count = source.indices.size();
  source.indexed = true;
  for (size_t i = 0; i < source.count; ++i) {
    if (source.indices[i] >= vertexCount) {
      context.fail(where, "index " + std::to_string(i) + " is " +
                              std::to_string(source.indices[i]) + ", but POSITION has only " +
                              std::to_string(vertexCount) + " vertices");
    }
  }
  return source;
}

void addFace(std::vector<glm::uvec3>& faces, uint32_t a, uint32_t b, uint32_t c) {
  if (a != b && b != c && a != c) faces.emplace_back(a, b, c);
}

// glTF 2.0 section 3.7.2.1: strips alternate their winding, fans share vertex 0.
std::vector<glm::uvec3> assembleFaces(Context& context, const PrimitiveRef& ref,
                                      const IndexSource& idx) {
  std::vector<glm::uvec3> faces;
  size_t n = idx.count;
  int mode = ref.primitive.mode;
  size_t triangles = mode == TINYGLTF_MODE_TRIANGLES ? n / 3 : (n >= 3 ? n - 2 : 0);
  context.charge(uint64_t(triangles) * sizeof(glm::uvec3), ref.where);
  faces.reserve(triangles);
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    for (size_t i = 0; i + 2 < n; i += 3) addFace(faces, idx[i], idx[i + 1], idx[i + 2]);
    if (n % 3 != 0) {
      context.warn(ref.where, std::to_string(n % 3) + " trailing vertices do not make a triangle");
    }
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (size_t i = 0; i < triangles; ++i) {
      size_t odd = i % 2;
      addFace(faces, idx[i], idx[i + 1 + odd], idx[i + 2 - odd]);
    }
  } else {  // TINYGLTF_MODE_TRIANGLE_FAN
    for (size_t i = 0; i < triangles; ++i) addFace(faces, idx[i + 1], idx[i + 2], idx[0]);
  }
  return faces;
}

// False (after a warning) for modes drawn as points or lines; fails for
// values that are no glTF mode at all.
bool isTriangleMode(Context& context, const PrimitiveRef& ref) {
  switch (ref.primitive.mode) {
    case TINYGLTF_MODE_TRIANGLES:
    case TINYGLTF_MODE_TRIANGLE_STRIP:
    case TINYGLTF_MODE_TRIANGLE_FAN: return true;
    case TINYGLTF_MODE_POINTS:
    case TINYGLTF_MODE_LINE:
    case TINYGLTF_MODE_LINE_LOOP:
    case TINYGLTF_MODE_LINE_STRIP:
      context.ignored("points and lines (primitive modes 0 to 3)", ref.where);
      return false;
    default:
      context.fail(ref.where + ".mode",
                   std::to_string(ref.primitive.mode) + " is not a glTF primitive mode (0..6)");
  }
}

}  // namespace

std::optional<TriangleMesh> buildPrimitive(Context& context, int mesh, int primitive,
                                           const UvMapping& uvMapping) {
  const tinygltf::Mesh& gltfMesh = context.model().meshes[size_t(mesh)];
  PrimitiveRef ref{gltfMesh.primitives[size_t(primitive)],
                   item("meshes", mesh) + "." + item("primitives", primitive)};
  if (!isTriangleMode(context, ref)) return std::nullopt;
  noteIgnoredAttributes(context, ref);
  TriangleMesh out;
  out.positions = readPositions(context, ref);
  size_t vertexCount = out.positions.size();
  out.normals = readNormals(context, ref, vertexCount);
  out.uvs = readUvs(context, ref, vertexCount, uvMapping);
  out.colors = readColors(context, ref, vertexCount);
  dropWhiteColors(out);
  out.faces = assembleFaces(context, ref, readIndexSource(context, ref, vertexCount));
  if (out.faces.empty()) {
    context.warn(ref.where, "no triangle with three distinct vertices; primitive skipped");
    return std::nullopt;
  }
  return out;
}

TriangleMesh mirrored(const TriangleMesh& mesh) {
  TriangleMesh out = mesh;
  for (glm::uvec3& face : out.faces) std::swap(face.y, face.z);
  return out;
}

}  // namespace rt::gltf
