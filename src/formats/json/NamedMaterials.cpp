#include "formats/json/NamedMaterials.hpp"

#include <optional>
#include <set>

#include "formats/common/SceneTextures.hpp"
#include "formats/json/ReferencedFiles.hpp"
#include "util/Text.hpp"

namespace rt {

namespace fs = std::filesystem;

namespace {

// What a named texture gives a material: a colour or a texture image.
struct NamedTexture {
  std::optional<glm::vec3> color;
  Material texture;  // diffuseTexture and texture set when it is an image
};

// {"name", "type": "constant", "colour"}, {"name", "type": "image", "image"}
// (its `offset_u`/`offset_v` are not read); other kinds are drawn with the
// missing-texture squares.
NamedTexture readNamedTexture(JsonObject& texture, const fs::path& sceneDir, Scene& scene) {
  NamedTexture out;
  const std::string type = lowercase(texture.required("type").string());
  if (type == "constant") {
    out.color = texture.required("colour").nonNegativeVec3();
  } else if (type == "image") {
    readTextureFile(texture.required("image"), sceneDir, out.texture, scene);
    for (const char* key : {"offset_u", "offset_v"}) {
      texture.ignoreWithWarning(key, "texture offsets are not read: the image starts at (0, 0)");
    }
  } else {
    texture.diagnostics().warn(texture.childPath("type"),
                               "a texture kind this renderer does not know; drawn with the "
                               "missing-texture squares");
    out.texture.texture = "missing texture";
    out.texture.diffuseTexture = addMissingTexture(scene);
  }
  return out;
}

// {"name", "type": "blinnphong", "ka", "kd", "ks", "alpha" (the exponent),
// "reflectance" (the mirror weight), "colour" | "texture" (a texture's name)}.
Material readNamedMaterial(JsonObject& material,
                           const std::map<std::string, NamedTexture>& textures) {
  Material out;
  if (std::optional<JsonNode> type = material.optional("type");
      type && lowercase(type->string()) != "blinnphong") {
    type->warn("read as a Blinn-Phong material");
  }
  out.kd = material.required("kd").nonNegativeFloat();
  out.ks = material.required("ks").nonNegativeFloat();
  if (std::optional<JsonNode> alpha = material.optional("alpha")) {
    out.specularExponent = alpha->positiveFloat();
  }
  if (std::optional<JsonNode> mirror = material.optional("reflectance")) {
    out.reflectivity = mirror->floatInRange(0.0f, 1.0f);
  }
  out.diffuseColor = glm::vec3(1.0f);
  if (std::optional<JsonNode> color = material.optional("colour")) {
    out.diffuseColor = color->nonNegativeVec3();
  }
  if (std::optional<JsonNode> name = material.optional("texture")) {
    const auto found = textures.find(name->string());
    if (found == textures.end())
      name->fail("no texture named '" + name->string() + "' in textures");
    if (found->second.color) {
      out.diffuseColor = *found->second.color;
    } else {
      out.texture = found->second.texture.texture;
      out.diffuseTexture = found->second.texture.diffuseTexture;
    }
  }
  material.ignoreWithWarning("ka", "'ka' ignored: there is no ambient term");
  return out;
}

// A list of named objects, read one by one; a name given twice is an error.
template <typename Read>
void readNamedList(JsonObject& owner, const char* key, Read read) {
  const std::optional<JsonNode> list = owner.optional(key);
  if (!list) return;
  std::set<std::string> seen;
  for (const JsonNode& node : list->array()) {
    JsonObject object = node.object();
    const JsonNode nameNode = object.required("name");
    const std::string name = nameNode.string();
    if (!seen.insert(name).second)
      nameNode.fail("a second " + std::string(key) + " entry named '" + name + "'");
    read(name, object);
    object.reportUnknownKeys();
  }
}

}  // namespace

NamedMaterials readNamedMaterials(JsonObject& sceneObject, const fs::path& sceneDir, Scene& scene) {
  std::map<std::string, NamedTexture> textures;
  readNamedList(sceneObject, "textures", [&](const std::string& name, JsonObject& texture) {
    textures[name] = readNamedTexture(texture, sceneDir, scene);
  });
  NamedMaterials materials;
  readNamedList(sceneObject, "materials", [&](const std::string& name, JsonObject& material) {
    scene.materials.push_back(readNamedMaterial(material, textures));
    materials[name] = static_cast<uint32_t>(scene.materials.size() - 1);
  });
  return materials;
}

uint32_t namedMaterial(const JsonNode& name, const NamedMaterials& materials) {
  const auto found = materials.find(name.string());
  if (found == materials.end()) {
    name.fail("no material named '" + name.string() + "' in the scene's materials");
  }
  return found->second;
}

}  // namespace rt
