// glTF materials, base colour, normal and metallic-roughness textures onto rt::Material
// (Blinn-Phong with mirror and refraction weights) and Scene::textures.
#pragma once

#include <filesystem>
#include <map>
#include <tuple>

#include "formats/gltf/GltfContext.hpp"
#include "formats/gltf/GltfMesh.hpp"
#include "scene/Scene.hpp"

namespace rt::gltf {

// The glTF default material (no `material` on a primitive) becomes a plain
// grey diffuse rt::Material, as in the JSON scenes, rather than the white
// rough metal of the glTF specification.
class MaterialTable {
 public:
  MaterialTable(Context& context, Scene& scene, std::filesystem::path baseDir);

  // Index into Scene::materials of glTF material `index` (-1: the default
  // material), converted and added on first use. Fails for a missing index.
  uint32_t material(int index, const std::string& where);

  // How primitives with this material map texture coordinates.
  UvMapping uvMapping(int index) const;

  // The radiance glTF material `index` emits as a light: emissiveFactor
  // times KHR_materials_emissive_strength; zero for the default material and
  // where an emissive texture makes it a glow (Material::glow: its detail
  // cannot be one light). Call after material(index).
  glm::vec3 emission(int index) const;

 private:
  // What a texture's texels are: sRGB-encoded colours, or data (normal maps).
  enum class Encoding { Srgb, Linear };

  int32_t texture(int textureIndex, Encoding encoding, const std::string& where);
  int32_t decodeImage(int image, Encoding encoding, TextureSampling sampling,
                      const std::string& where);
  TextureSampling samplingOf(int textureIndex, const std::string& where);
  bool readsSharedUvs(int index, int texCoord, const tinygltf::ExtensionMap& extensions,
                      const std::string& where);
  void addNormalMap(int index, Material& converted);
  void addGlow(int index, glm::vec3 emissive, Material& converted);
  void addMetalRoughTexture(int index, Material& converted);
  void addTransmissionTexture(int index, Material& converted);
  glm::vec2 metallicRoughnessAverage(const tinygltf::TextureInfo& info, const std::string& where);
  // The image of glTF texture `textureIndex`, or -1 when it has none we can read.
  int imageOf(int textureIndex, const std::string& where);
  ImageRgba8 readImage(int image, const std::string& where, std::string& source);
  // Adds a decoded image (or a copy of one) to the budget; fails past it.
  void countDecodedBytes(const ImageRgba8& image, int index, const std::string& where);
  ImageRgba8 decodeImageData(int image, const std::string& where, std::string& source);

  Context& context_;
  Scene& scene_;
  std::filesystem::path baseDir_;
  std::map<int, uint32_t> materials_;   // glTF material -> Scene::materials
  std::map<int, glm::vec3> emissions_;  // glTF material -> emitted radiance
  // glTF image, as read -> Scene::textures
  std::map<std::tuple<int, Encoding, TextureSampling>, int32_t> images_;
  std::map<int, glm::vec2> averages_;  // glTF image -> mean (metallic, roughness)
  uint64_t decodedBytes_ = 0;          // all images decoded so far, bounded
};

}  // namespace rt::gltf
