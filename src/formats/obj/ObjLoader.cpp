#include "formats/obj/ObjLoader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "formats/common/Diagnostics.hpp"
#include "formats/common/FileBytes.hpp"
#include "formats/common/MeshNormals.hpp"
#include "formats/common/MessageText.hpp"
#include "formats/common/ModelFraming.hpp"
#include "formats/common/SceneTextures.hpp"
#include "formats/common/VertexColors.hpp"
#include "io/Image.hpp"
#include "util/Error.hpp"
#include "util/Text.hpp"

// The includes must stay between the two (clang-format would sort them).
// clang-format off
#include "util/ThirdPartyBegin.hpp"
#include <tiny_obj_loader.h>
#include "util/ThirdPartyEnd.hpp"
// clang-format on

namespace rt {
namespace {

namespace fs = std::filesystem;

// tinyobjloader's warnings name a line each; a broken file can have a million.
constexpr size_t kMaxParserWarnings = 8;

std::string firstLine(const std::string& text) {
  const size_t end = text.find('\n');
  return end == std::string::npos ? text : text.substr(0, end);
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!line.empty()) out.push_back(line);
  }
  return out;
}

// Names after every `mtllib` (several per line are allowed), each once.
std::vector<std::string> materialLibraries(std::string_view obj) {
  std::vector<std::string> names;
  size_t start = 0;
  while (start < obj.size()) {
    size_t end = obj.find('\n', start);
    if (end == std::string_view::npos) end = obj.size();
    std::string_view line = obj.substr(start, end - start);
    start = end + 1;
    size_t first = line.find_first_not_of(" \t");
    if (first == std::string_view::npos || line.substr(first, 7) != "mtllib ") continue;
    std::istringstream words{std::string(line.substr(first + 7))};
    for (std::string name; words >> name;) {
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    }
  }
  return names;
}

// tinyobjloader turns a `vw` (skin weight) line's joint id into an int
// without a range check, undefined for huge values (found by fuzz_obj). The
// renderer has no use for skin weights: those lines are blanked out before
// parsing (same length, so line numbers in messages stay right).
std::string withoutSkinWeights(std::string_view obj) {
  std::string text(obj);
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find_first_of("\r\n", start);  // tinyobjloader ends lines at either
    if (end == std::string::npos) end = text.size();
    const size_t first = text.find_first_not_of(" \t", start);  // its lines may start with blanks
    if (first < end && text.compare(first, 2, "vw") == 0 &&
        (first + 2 == end || text[first + 2] == ' ' || text[first + 2] == '\t')) {
      std::fill(text.begin() + static_cast<std::ptrdiff_t>(first),
                text.begin() + static_cast<std::ptrdiff_t>(end), ' ');
    }
    start = end + 1;
  }
  return text;
}

glm::vec3 colour(const tinyobj::real_t* rgb) {
  glm::vec3 c(rgb[0], rgb[1], rgb[2]);
  for (int i = 0; i < 3; ++i) c[i] = std::isfinite(c[i]) ? std::max(c[i], 0.0f) : 0.0f;
  return c;
}

// Ke beyond this is taken as this (far brighter than any lamp of a real
// model), so that a light's intensity, radiance times area, stays finite.
constexpr float kMaxEmission = 1e6f;

float finiteOr(float value, float fallback) { return std::isfinite(value) ? value : fallback; }

// Every texel has red = green = blue: a height map, not a normal map.
// A `map_d` image as coverage in its alpha channel: the file's own alpha
// where it has one, else its grey level (red), as masks are usually drawn.
void coverageInAlpha(ImageRgba8& image) {
  bool opaque = true;
  for (size_t i = 3; i < image.rgba.size(); i += 4) opaque = opaque && image.rgba[i] == 255;
  if (!opaque) return;
  for (size_t i = 0; i + 3 < image.rgba.size(); i += 4) image.rgba[i + 3] = image.rgba[i];
}

bool isGrey(const ImageRgba8& image) {
  for (size_t i = 0; i + 2 < image.rgba.size(); i += 4) {
    if (image.rgba[i] != image.rgba[i + 1] || image.rgba[i] != image.rgba[i + 2]) return false;
  }
  return true;
}

class ObjImporter {
 public:
  ObjImporter(const fs::path& file, const WorldTransform& placement)
      : file_(file),
        folder_(file.parent_path()),
        placement_(placement),
        diagnostics_(file.string()) {}

  Scene run(std::string_view obj, std::string_view mtl) {
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromString(withoutSkinWeights(obj), std::string(mtl), config)) {
      const std::string error = firstLine(reader.Error());
      diagnostics_.fail("", error.empty() ? "not a readable OBJ file" : error);
    }
    reportParserWarnings(reader.Warning());
    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    addMaterials(reader.GetMaterials());
    for (const tinyobj::shape_t& shape : reader.GetShapes()) addFaces(shape, attrib);
    finishMeshes();
    if (scene_.shapes.empty()) diagnostics_.warn("", "no faces: nothing to draw");
    scene_.warnings = diagnostics_.takeWarnings();
    return std::move(scene_);
  }

 private:
  // Corners sharing position, texture coordinate and normal become one vertex.
  using CornerKey = std::tuple<int, int, int>;

  struct PendingMesh {
    TriangleMesh mesh;
    std::map<CornerKey, uint32_t> vertexOf;
    bool allNormals = true;
    bool allUvs = true;
    std::string label;
  };

  void reportParserWarnings(const std::string& text) {
    const std::vector<std::string> all = lines(text);
    for (size_t i = 0; i < std::min(all.size(), kMaxParserWarnings); ++i) {
      diagnostics_.warn("", all[i]);
    }
    if (all.size() > kMaxParserWarnings) {
      diagnostics_.warn("", std::to_string(all.size() - kMaxParserWarnings) +
                                " more warnings of the OBJ reader not shown");
    }
  }

  void addMaterials(const std::vector<tinyobj::material_t>& materials) {
    for (const tinyobj::material_t& source : materials) {
      Material out;
      out.kd = 1.0f;
      out.diffuseColor = colour(source.diffuse);
      out.specularColor = colour(source.specular);
      out.ks = glm::length(out.specularColor) > 0.0f ? 1.0f : 0.0f;
      out.specularExponent = std::clamp(finiteOr(source.shininess, 1.0f), 0.0f, 1e4f);
      const float opacity = std::clamp(finiteOr(source.dissolve, 1.0f), 0.0f, 1.0f);
      out.transmission = 1.0f - opacity;
      out.ior = std::clamp(finiteOr(source.ior, 1.0f), 1e-3f, 1e3f);
      applyIlluminationModel(source, out);
      if (!source.diffuse_texname.empty()) addDiffuseTexture(source, out);
      addNormalMap(source, out);
      if (!source.alpha_texname.empty()) addAlphaMap(source, out);
      if (!source.emissive_texname.empty()) {
        diagnostics_.warn("material '" + source.name + "'",
                          "emission texture map_Ke ignored (Ke alone decides the glow)");
      }
      materialNames_.push_back(source.name);
      materialEmission_.push_back(glm::min(colour(source.emission), glm::vec3(kMaxEmission)));
      scene_.materials.push_back(std::move(out));
    }
    defaultMaterial_ = static_cast<uint32_t>(scene_.materials.size());
    scene_.materials.push_back(Material{});
    materialEmission_.push_back(glm::vec3(0.0f));
  }

  // The MTL illumination models that trace rays: 3 and 5 reflect (a mirror
  // of weight max(Ks)), 6 and 7 refract (the transmission filter Tf's mean,
  // where d or Tr give no transparency of their own), as in McGuire's
  // Cornell boxes. The other models are Blinn-Phong as read.
  static void applyIlluminationModel(const tinyobj::material_t& source, Material& out) {
    if (source.illum == 3 || source.illum == 5) {
      const glm::vec3 ks = colour(source.specular);
      out.reflectivity = std::min(1.0f, std::max({ks.x, ks.y, ks.z}));
    }
    if (source.illum == 6 || source.illum == 7) {
      const glm::vec3 tf = colour(source.transmittance);
      out.transmission = std::max(out.transmission, std::min(1.0f, (tf.x + tf.y + tf.z) / 3.0f));
    }
  }

  void addDiffuseTexture(const tinyobj::material_t& source, Material& out) {
    const fs::path written = portablePath(source.diffuse_texname);
    out.textureTintedByColor = true;
    const std::string where = "material '" + source.name + "'";
    try {
      if (useDiffuseTextureFile(scene_, out, (folder_ / written).lexically_normal())) return;
    } catch (const Error& error) {
      diagnostics_.fail(where, error.what());
    }
    diagnostics_.warn(where, "texture file not found: " + written.string() +
                                 "; drawn with the missing-texture squares");
    out.texture = written;
  }

  // `norm`, else `map_Bump` (where Blender's exporter writes a normal map,
  // its strength in `-bm`): a tangent-space normal map, as glTF's. A grey
  // `map_Bump` is a height map, which the renderer cannot use: a warning.
  void addNormalMap(const tinyobj::material_t& source, Material& out) {
    const bool named = !source.normal_texname.empty();
    const std::string& written = named ? source.normal_texname : source.bump_texname;
    if (written.empty()) return;
    const std::string where = "material '" + source.name + "'";
    const fs::path found = (folder_ / portablePath(written)).lexically_normal();
    auto known = normalMaps_.find(found);
    if (known == normalMaps_.end())
      known = normalMaps_.emplace(found, readNormalMap(found, named, where)).first;
    out.normalTexture = known->second;
    if (!named && out.normalTexture >= 0) {
      out.normalScale = std::clamp(finiteOr(source.bump_texopt.bump_multiplier, 1.0f), -1e3f, 1e3f);
    }
  }

  // `map_d`: an alpha mask that cuts holes where it is below one half (the
  // leaves and chains of Sponza-like scenes); RT_FEATURE_ALPHA_CUTOUTS.
  void addAlphaMap(const tinyobj::material_t& source, Material& out) {
    const std::string where = "material '" + source.name + "'";
    const fs::path found = (folder_ / portablePath(source.alpha_texname)).lexically_normal();
    auto known = alphaMaps_.find(found);
    if (known == alphaMaps_.end())
      known = alphaMaps_.emplace(found, readAlphaMap(found, where)).first;
    if (known->second < 0) return;
    out.alphaMode = Material::Alpha::Mask;
    out.alphaCutoff = 0.5f;
    out.alphaTexture = known->second;
  }

  // Index in scene_.textures of the coverage of `file` (coverageInAlpha), or
  // -1 after a warning.
  int32_t readAlphaMap(const fs::path& file, const std::string& where) {
    std::error_code ignored;
    if (!fs::is_regular_file(file, ignored)) {
      diagnostics_.warn(where, "map_d: texture file not found: " + file.string() + "; no holes");
      return -1;
    }
    ImageRgba8 image;
    try {
      image = readImageRgba8(file);
    } catch (const Error& error) {
      diagnostics_.fail(where, std::string("map_d: cannot use texture: ") + error.what());
    }
    coverageInAlpha(image);
    scene_.textures.push_back({file.string() + " (coverage)", std::move(image), true});
    return static_cast<int32_t>(scene_.textures.size() - 1);
  }

  // Index in scene_.textures of the normal map `file`, or -1 after a warning.
  int32_t readNormalMap(const fs::path& file, bool named, const std::string& where) {
    const std::string key = named ? "norm" : "map_Bump";
    std::error_code ignored;
    if (!fs::is_regular_file(file, ignored)) {
      diagnostics_.warn(where,
                        key + ": texture file not found: " + file.string() + "; no normal map");
      return -1;
    }
    ImageRgba8 image;
    try {
      image = readImageRgba8(file);
    } catch (const Error& error) {
      diagnostics_.fail(where, key + ": cannot use texture: " + error.what());
    }
    if (!named && isGrey(image)) {
      diagnostics_.warn(where, "map_Bump " + file.filename().string() +
                                   " is a height map (grey); bump maps are not supported, ignored");
      return -1;
    }
    scene_.textures.push_back({file.string(), std::move(image), true});
    return static_cast<int32_t>(scene_.textures.size() - 1);
  }

  // Faces of a material with `Ke` glow: their mesh becomes an area light of
  // that radiance (the last shape added).
  void addEmitterOf(uint32_t material, const std::string& label) {
    const glm::vec3 radiance = materialEmission_.at(material);
    if (radiance == glm::vec3(0.0f)) return;
    const auto shape = static_cast<uint32_t>(scene_.shapes.size() - 1);
    if (!addRadianceEmitter(scene_, shape, radiance)) {
      diagnostics_.warn(label, "Ke: the faces have no area to emit from; not a light");
    }
  }

  uint32_t materialSlot(int id) const {
    if (id < 0 || static_cast<size_t>(id) >= defaultMaterial_) return defaultMaterial_;
    return static_cast<uint32_t>(id);
  }

  // The index, checked against the attribute's count (tinyobjloader has
  // already made relative indices absolute; -1 means "not given").
  int checkedIndex(int index, size_t count, const char* what, const std::string& where) const {
    if (index < -1 || (index >= 0 && static_cast<size_t>(index) >= count)) {
      diagnostics_.fail(where, std::string("refers to ") + what + " " + std::to_string(index + 1) +
                                   ", the file has " + std::to_string(count));
    }
    return index;
  }

  uint32_t vertexOf(PendingMesh& pending, const tinyobj::index_t& corner,
                    const tinyobj::attrib_t& attrib, const std::string& where) {
    const int v = checkedIndex(corner.vertex_index, attrib.vertices.size() / 3, "vertex", where);
    if (v < 0) diagnostics_.fail(where, "has a corner without a vertex");
    const int t = checkedIndex(corner.texcoord_index, attrib.texcoords.size() / 2,
                               "texture coordinate", where);
    const int n = checkedIndex(corner.normal_index, attrib.normals.size() / 3, "normal", where);
    const CornerKey key{v, t, n};
    if (const auto found = pending.vertexOf.find(key); found != pending.vertexOf.end()) {
      return found->second;
    }
    const size_t vi = static_cast<size_t>(v);
    glm::vec3 position(attrib.vertices[3 * vi], attrib.vertices[3 * vi + 1],
                       attrib.vertices[3 * vi + 2]);
    if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z)) {
      diagnostics_.fail(where, "vertex " + std::to_string(v + 1) + " is not a finite point");
    }
    TriangleMesh& mesh = pending.mesh;
    mesh.positions.push_back(position);
    glm::vec3 normal(0.0f);
    if (n >= 0) {
      const size_t ni = static_cast<size_t>(n);
      normal =
          glm::vec3(attrib.normals[3 * ni], attrib.normals[3 * ni + 1], attrib.normals[3 * ni + 2]);
    }
    pending.allNormals = pending.allNormals && n >= 0;
    mesh.normals.push_back(normal);
    glm::vec2 uv(0.0f);
    if (t >= 0) {
      const size_t ti = static_cast<size_t>(t);
      uv = glm::vec2(finiteOr(attrib.texcoords[2 * ti], 0.0f),
                     finiteOr(attrib.texcoords[2 * ti + 1], 0.0f));
    }
    pending.allUvs = pending.allUvs && t >= 0;
    // OBJ's v runs up the image; the renderer's rows run down.
    mesh.uvs.emplace_back(uv.x, 1.0f - uv.y);
    // Colours after a vertex's x y z (MeshLab's and ZBrush's extension):
    // tinyobjloader keeps them only when every vertex has them.
    if (attrib.colors.size() == attrib.vertices.size()) {
      mesh.colors.push_back(linearFromDisplayColor(
          {attrib.colors[3 * vi], attrib.colors[3 * vi + 1], attrib.colors[3 * vi + 2]}));
    }
    const auto index = static_cast<uint32_t>(mesh.positions.size() - 1);
    pending.vertexOf.emplace(key, index);
    return index;
  }

  void addFaces(const tinyobj::shape_t& shape, const tinyobj::attrib_t& attrib) {
    const tinyobj::mesh_t& source = shape.mesh;
    size_t offset = 0;
    for (size_t face = 0; face < source.num_face_vertices.size(); ++face) {
      const size_t corners = source.num_face_vertices[face];
      const std::string where = (shape.name.empty() ? "" : "object '" + shape.name + "' ") +
                                "face " + std::to_string(face + 1);
      if (offset + corners > source.indices.size()) diagnostics_.fail(where, "is cut short");
      if (corners == 3) {
        const int id = face < source.material_ids.size() ? source.material_ids[face] : -1;
        PendingMesh& pending = meshFor(materialSlot(id));
        glm::uvec3 triangle;
        for (size_t c = 0; c < 3; ++c) {
          triangle[static_cast<int>(c)] =
              vertexOf(pending, source.indices[offset + c], attrib, where);
        }
        pending.mesh.faces.push_back(triangle);
      }
      offset += corners;
    }
  }

  PendingMesh& meshFor(uint32_t material) {
    auto found = pending_.find(material);
    if (found != pending_.end()) return found->second;
    PendingMesh& added = pending_[material];
    added.label = material < materialNames_.size() ? "material '" + materialNames_[material] + "'"
                                                   : std::string("no material");
    return added;
  }

  void finishMeshes() {
    for (auto& [material, pending] : pending_) {
      TriangleMesh& mesh = pending.mesh;
      if (mesh.faces.empty()) continue;
      if (pending.allNormals) {
        completeVertexNormals(mesh);
      } else {
        mesh.normals.clear();
      }
      if (!pending.allUvs) mesh.uvs.clear();
      dropWhiteColors(mesh);
      scene_.meshes.push_back(std::move(mesh));
      Shape shape;
      shape.geometry = MeshInstance{static_cast<uint32_t>(scene_.meshes.size() - 1), placement_};
      shape.material = material;
      shape.label = file_.filename().string() + ": " + pending.label;
      scene_.shapes.push_back(std::move(shape));
      addEmitterOf(material, pending.label);
    }
  }

  fs::path file_;
  fs::path folder_;
  WorldTransform placement_;
  Diagnostics diagnostics_;
  Scene scene_;
  uint32_t defaultMaterial_ = 0;
  std::vector<std::string> materialNames_;   // of the file's materials, by index
  std::vector<glm::vec3> materialEmission_;  // Ke of every material, the default's last
  std::map<uint32_t, PendingMesh> pending_;
  std::map<fs::path, int32_t> normalMaps_;  // each file read once; -1: not used
  std::map<fs::path, int32_t> alphaMaps_;   // likewise
};

// The texts of the file's material libraries, one after the other; a
// missing one is a warning.
std::string readMaterialLibraries(std::string_view obj, const fs::path& file,
                                  std::vector<std::string>& warnings) {
  std::string all;
  for (const std::string& name : materialLibraries(obj)) {
    const fs::path written = portablePath(name);
    std::string text;
    const std::string problem = readFileBytes(file.parent_path() / written, text);
    if (!problem.empty()) {
      warnings.push_back(file.string() + ": material library " + written.string() + ": " + problem +
                         "; its materials are drawn in the default grey");
      continue;
    }
    all += text;
    all += '\n';
  }
  return all;
}

}  // namespace

Scene parseObjPart(std::string_view obj, std::string_view mtl, const fs::path& file,
                   const WorldTransform& placement) {
  return withPrintableErrors([&] {
    Scene scene = ObjImporter(file, placement).run(obj, mtl);
    makePrintable(scene.warnings);
    return scene;
  });
}

Scene loadObjPart(const fs::path& file, const WorldTransform& placement) {
  const std::string obj = readFileOrThrow(file);
  std::vector<std::string> warnings;
  const std::string mtl = readMaterialLibraries(obj, file, warnings);
  Scene scene = parseObjPart(obj, mtl, file, placement);
  makePrintable(warnings);
  scene.warnings.insert(scene.warnings.begin(), warnings.begin(), warnings.end());
  return scene;
}

Scene loadObjScene(const fs::path& file) {
  Scene scene;
  appendScenePart(scene, loadObjPart(file, WorldTransform(1.0)));
  scene.sourcePath = file;
  frameModelScene(scene, {"an OBJ file", "Ke"});
  return scene;
}

bool isObjFile(const fs::path& file) { return hasExtension(file, {".obj"}); }

}  // namespace rt
