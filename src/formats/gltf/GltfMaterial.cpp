#include "formats/gltf/GltfMaterial.hpp"

#include <algorithm>
#include <cmath>

#include "formats/common/FileBytes.hpp"
#include "formats/gltf/GltfDocument.hpp"
#include "metal_rough.h"
#include "util/Error.hpp"

namespace rt::gltf {
namespace {

namespace fs = std::filesystem;

// The images decoded for one file together stay below this (each image is
// also limited to 2^26 pixels by io/Image): a few kilobytes of PNG can
// inflate to hundreds of megabytes, and one file may name it many times.
constexpr uint64_t kMaxTextureBytes = uint64_t(1) << 30;

// Emissive strengths beyond this are taken as this (far brighter than any
// lamp), so that a light's intensity, radiance times area, stays finite.
constexpr float kMaxEmissiveStrength = 1e6f;

double finiteNumber(const Context& context, double value, const std::string& where) {
  if (!std::isfinite(value)) context.fail(where, "is not a finite number");
  return value;
}

// A factor the specification keeps in [0, 1]; values outside are clamped.
float unitFactor(Context& context, double value, const std::string& where) {
  finiteNumber(context, value, where);
  if (value < 0.0 || value > 1.0) context.warn(where, "outside [0, 1]; clamped");
  return static_cast<float>(std::clamp(value, 0.0, 1.0));
}

// The RGB of a colour factor of `size` numbers (baseColorFactor: RGBA,
// emissiveFactor: RGB), each in [0, 1].
glm::vec3 colourFactor(Context& context, const std::vector<double>& factor, size_t size,
                       const std::string& where) {
  if (factor.size() != size) {
    context.fail(where, "has " + std::to_string(factor.size()) + " numbers, " +
                            std::to_string(size) + " are required");
  }
  glm::vec3 color;
  for (int c = 0; c < 3; ++c) {
    color[c] = unitFactor(context, factor[size_t(c)], where + "[" + std::to_string(c) + "]");
  }
  return color;
}

// A number inside an extension object, `fallback` when absent.
double extensionNumber(const Context& context, const tinygltf::ExtensionMap& extensions,
                       const std::string& extension, const std::string& key, double fallback,
                       const std::string& where) {
  auto found = extensions.find(extension);
  if (found == extensions.end() || !found->second.IsObject() || !found->second.Has(key)) {
    return fallback;
  }
  const tinygltf::Value& value = found->second.Get(key);
  std::string path = where + ".extensions." + extension + "." + key;
  if (!value.IsNumber()) context.fail(path, "expected a number");
  return finiteNumber(context, value.GetNumberAsDouble(), path);
}

bool hasExtension(const tinygltf::ExtensionMap& extensions, const std::string& name,
                  const char* key) {
  auto found = extensions.find(name);
  return found != extensions.end() && found->second.IsObject() && found->second.Has(key);
}

void noteIgnoredFeatures(Context& context, const tinygltf::Material& gltf,
                         const std::string& where) {
  if (gltf.occlusionTexture.index >= 0) context.ignored("occlusion maps", where);
  if (hasExtension(gltf.extensions, "KHR_materials_volume", "attenuationDistance") ||
      hasExtension(gltf.extensions, "KHR_materials_volume", "attenuationColor")) {
    context.ignored("volume attenuation (KHR_materials_volume)", where);
  }
}

// alphaMode, alphaCutoff and the base colour factor's alpha (the base colour
// texture's alpha joins them in MaterialTable::material). An unknown mode is
// drawn opaque, with a warning.
void convertAlpha(Context& context, const tinygltf::Material& gltf, const std::string& where,
                  Material& out) {
  if (gltf.alphaMode == "OPAQUE") return;
  if (gltf.alphaMode == "MASK") {
    out.alphaMode = Material::Alpha::Mask;
    double cutoff = finiteNumber(context, gltf.alphaCutoff, where + ".alphaCutoff");
    if (cutoff < 0.0) context.warn(where + ".alphaCutoff", "negative; taken as 0");
    out.alphaCutoff = static_cast<float>(std::max(cutoff, 0.0));
  } else if (gltf.alphaMode == "BLEND") {
    out.alphaMode = Material::Alpha::Blend;
  } else {
    context.warn(where + ".alphaMode",
                 "unknown mode \"" + gltf.alphaMode + "\" (OPAQUE, MASK or BLEND); drawn opaque");
    return;
  }
  const std::vector<double>& base = gltf.pbrMetallicRoughness.baseColorFactor;
  if (base.size() == 4) {
    out.alphaFactor =
        unitFactor(context, base[3], where + ".pbrMetallicRoughness.baseColorFactor[3]");
  }
}

// glTF metallic-roughness onto the Blinn-Phong rt::Material (shaders/
// metal_rough.h, which the kernels share for textures' texels), with
// m = metallic, r = roughness (factor times the mean of the
// metallic-roughness texture, if any: the kernels take each texel where the
// texture reads the base colour's coordinates), t = transmission:
//   diffuseColor     = baseColor.rgb
//   transmission     = KHR_materials_transmission.transmissionFactor (default 0)
//   ior              = KHR_materials_ior.ior (default 1.5; below 1 is taken as 1.5)
//   tintedMirror     : mirror reflections times specularColor, the metal's base colour
//   tintedTransmission: transmitted light times the base colour
//   thinWalled       : without KHR_materials_volume.thicknessFactor > 0 (glTF's thin-walled
//                      default): transmitted light goes on unbent
Material convertMaterial(Context& context, const tinygltf::Material& gltf, const std::string& where,
                         glm::vec2 textureMetallicRoughness) {
  const tinygltf::PbrMetallicRoughness& pbr = gltf.pbrMetallicRoughness;
  std::string pbrWhere = where + ".pbrMetallicRoughness";
  glm::vec3 base = colourFactor(context, pbr.baseColorFactor, 4, pbrWhere + ".baseColorFactor");
  float m = unitFactor(context, pbr.metallicFactor, pbrWhere + ".metallicFactor") *
            textureMetallicRoughness.x;
  float r = unitFactor(context, pbr.roughnessFactor, pbrWhere + ".roughnessFactor") *
            textureMetallicRoughness.y;
  float t = unitFactor(context,
                       extensionNumber(context, gltf.extensions, "KHR_materials_transmission",
                                       "transmissionFactor", 0.0, where),
                       where + ".extensions.KHR_materials_transmission.transmissionFactor");
  double ior = extensionNumber(context, gltf.extensions, "KHR_materials_ior", "ior", 1.5, where);
  double thickness = extensionNumber(context, gltf.extensions, "KHR_materials_volume",
                                     "thicknessFactor", 0.0, where);
  if (ior < 1.0) {
    context.warn(where + ".extensions.KHR_materials_ior.ior", "below 1; using 1.5");
    ior = 1.5;
  }

  Material out;
  out.diffuseColor = base;
  out.kd = gpu::metalRoughKd(m, t);
  out.specularColor = glm::mix(glm::vec3(1.0f), base, m);
  out.specularExponent = gpu::metalRoughExponent(r);
  out.ks = gpu::metalRoughKs(m, out.specularExponent);
  out.reflectivity = gpu::metalRoughReflectivity(m, r);
  out.tintedMirror = true;
  out.tintedTransmission = true;
  out.thinWalled = !(thickness > 0.0);
  out.metallic = m;  // the kernels' specular colour mixes in the textured base colour
  out.roughness = r;
  out.transmission = t;
  out.ior = static_cast<float>(ior);
  convertAlpha(context, gltf, where, out);
  noteIgnoredFeatures(context, gltf, where);
  return out;
}

// emissiveFactor times KHR_materials_emissive_strength: the radiance an
// emissive material emits, times its emissive texture where it has one.
glm::vec3 emissiveColour(Context& context, const tinygltf::Material& gltf,
                         const std::string& where) {
  glm::vec3 colour = colourFactor(context, gltf.emissiveFactor, 3, where + ".emissiveFactor");
  double strength = extensionNumber(context, gltf.extensions, "KHR_materials_emissive_strength",
                                    "emissiveStrength", 1.0, where);
  if (strength < 0.0) {
    context.warn(where + ".extensions.KHR_materials_emissive_strength.emissiveStrength",
                 "negative; taken as 0");
    strength = 0.0;
  }
  return colour * static_cast<float>(std::min(strength, double(kMaxEmissiveStrength)));
}

// KHR_materials_unlit: the surface shows its base colour (factor times
// texture) whatever the lights, as scans and baked scenes are made to be
// seen: a glow of it, times the vertex colours as base colours are (it
// lights nothing, and still casts shadows). Its alpha stays.
void makeUnlit(Material& out) {
  out.glow = out.diffuseColor;
  out.glowTexture = out.diffuseTexture;
  out.glowTimesVertexColors = true;
  out.kd = out.ks = out.reflectivity = out.transmission = 0.0f;
  out.metallic = 0.0f;
  out.tintedMirror = out.tintedTransmission = out.thinWalled = false;
}

// A sampler's wrapS or wrapT; an unknown mode repeats, with a warning.
TextureSampling::Wrap wrapMode(Context& context, int mode, const std::string& where) {
  switch (mode) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT: return TextureSampling::Wrap::Repeat;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return TextureSampling::Wrap::Clamp;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return TextureSampling::Wrap::Mirror;
    default:
      context.warn(where, "unknown wrap mode " + std::to_string(mode) + "; repeats");
      return TextureSampling::Wrap::Repeat;
  }
}

Material defaultMaterial() {
  Material out;
  out.diffuseColor = glm::vec3(0.8f);
  out.kd = 1.0f;
  out.ks = 0.0f;
  return out;
}

// A texture's texture coordinate set and KHR_texture_transform, as a 3x3 UV
// matrix (translation * rotation * scale, rotation counter-clockwise in UV
// space).
UvMapping uvMappingOf(const Context& context, int texCoord,
                      const tinygltf::ExtensionMap& extensions, const std::string& where) {
  UvMapping mapping;
  mapping.set = std::max(texCoord, 0);
  auto found = extensions.find("KHR_texture_transform");
  if (found == extensions.end() || !found->second.IsObject()) return mapping;
  const tinygltf::Value& ext = found->second;
  std::string path = where + ".extensions.KHR_texture_transform";
  auto number = [&](const tinygltf::Value& v, const std::string& key) {
    if (!v.IsNumber()) context.fail(path + "." + key, "expected a number");
    return static_cast<float>(finiteNumber(context, v.GetNumberAsDouble(), path + "." + key));
  };
  auto pair = [&](const char* key, glm::vec2 fallback) {
    if (!ext.Has(key)) return fallback;
    const tinygltf::Value& v = ext.Get(key);
    if (!v.IsArray() || v.ArrayLen() != 2) context.fail(path + "." + key, "expected 2 numbers");
    return glm::vec2(number(v.Get(0), key), number(v.Get(1), key));
  };
  glm::vec2 offset = pair("offset", glm::vec2(0.0f));
  glm::vec2 scale = pair("scale", glm::vec2(1.0f));
  float rotation = ext.Has("rotation") ? number(ext.Get("rotation"), "rotation") : 0.0f;
  if (ext.Has("texCoord")) mapping.set = std::max(int(number(ext.Get("texCoord"), "texCoord")), 0);
  float c = std::cos(rotation), s = std::sin(rotation);
  // Column-major: u' = c sx u + s sy v + ox,  v' = -s sx u + c sy v + oy.
  mapping.transform = glm::mat3(glm::vec3(c * scale.x, -s * scale.x, 0.0f),
                                glm::vec3(s * scale.y, c * scale.y, 0.0f), glm::vec3(offset, 1.0f));
  return mapping;
}

}  // namespace

MaterialTable::MaterialTable(Context& context, Scene& scene, fs::path baseDir)
    : context_(context), scene_(scene), baseDir_(std::move(baseDir)) {}

uint32_t MaterialTable::material(int index, const std::string& where) {
  if (auto found = materials_.find(index); found != materials_.end()) return found->second;
  const auto& gltfMaterials = context_.model().materials;
  if (index >= 0 && size_t(index) >= gltfMaterials.size()) {
    context_.fail(where, "material " + std::to_string(index) + " does not exist (the file has " +
                             std::to_string(gltfMaterials.size()) + ")");
  }
  Material converted = defaultMaterial();
  if (index >= 0) {
    std::string name = item("materials", index);
    const tinygltf::Material& gltf = gltfMaterials[size_t(index)];
    glm::vec2 average =
        metallicRoughnessAverage(gltf.pbrMetallicRoughness.metallicRoughnessTexture,
                                 name + ".pbrMetallicRoughness.metallicRoughnessTexture");
    converted = convertMaterial(context_, gltf, name, average);
    const bool unlit = gltf.extensions.count("KHR_materials_unlit") > 0;
    glm::vec3 emissive = unlit ? glm::vec3(0.0f) : emissiveColour(context_, gltf, name);
    if (gltf.emissiveTexture.index < 0) {
      emissions_[index] = emissive;
    } else if (emissive != glm::vec3(0.0f)) {
      addGlow(index, emissive, converted);
    }
    const tinygltf::TextureInfo& info = gltf.pbrMetallicRoughness.baseColorTexture;
    if (info.index >= 0) {
      std::string infoWhere = name + ".pbrMetallicRoughness.baseColorTexture";
      uvMappingOf(context_, info.texCoord, info.extensions, infoWhere);  // validates it now
      converted.diffuseTexture = texture(info.index, Encoding::Srgb, infoWhere);
      if (converted.diffuseTexture >= 0) {
        converted.texture = scene_.textures[size_t(converted.diffuseTexture)].source;
        converted.textureTintedByColor = true;  // glTF: base colour = factor * texture
        if (converted.alphaMode != Material::Alpha::Opaque) {
          converted.alphaTexture = converted.diffuseTexture;  // its alpha is coverage
        }
      }
    }
    if (unlit) {
      makeUnlit(converted);
    } else {
      addNormalMap(index, converted);
      addMetalRoughTexture(index, converted);
      addTransmissionTexture(index, converted);
    }
  }
  scene_.materials.push_back(std::move(converted));
  uint32_t added = static_cast<uint32_t>(scene_.materials.size() - 1);
  materials_.emplace(index, added);
  return added;
}

glm::vec3 MaterialTable::emission(int index) const {
  auto found = emissions_.find(index);
  return found == emissions_.end() ? glm::vec3(0.0f) : found->second;
}

// The base colour texture's mapping, else the normal map's: the one set of
// texture coordinates a primitive's vertices carry.
UvMapping MaterialTable::uvMapping(int index) const {
  if (index < 0 || size_t(index) >= context_.model().materials.size()) return {};
  const tinygltf::Material& gltf = context_.model().materials[size_t(index)];
  const tinygltf::TextureInfo& info = gltf.pbrMetallicRoughness.baseColorTexture;
  if (info.index >= 0) {
    return uvMappingOf(context_, info.texCoord, info.extensions, item("materials", index));
  }
  const tinygltf::NormalTextureInfo& normal = gltf.normalTexture;
  if (normal.index >= 0) {
    return uvMappingOf(context_, normal.texCoord, normal.extensions, item("materials", index));
  }
  return {};
}

// Whether a texture of glTF material `index` reads the texture coordinates
// its base colour texture reads (a vertex carries one set); warns if not.
bool MaterialTable::readsSharedUvs(int index, int texCoord,
                                   const tinygltf::ExtensionMap& extensions,
                                   const std::string& where) {
  UvMapping own = uvMappingOf(context_, texCoord, extensions, where);
  UvMapping shared = uvMapping(index);
  if (own.set == shared.set && own.transform == shared.transform) return true;
  context_.warn(where, "reads other texture coordinates than the base colour texture; ignored");
  return false;
}

// The emissive texture of glTF material `index` times `emissive`, as a glow:
// its detail cannot be one light.
void MaterialTable::addGlow(int index, glm::vec3 emissive, Material& converted) {
  const tinygltf::TextureInfo& info = context_.model().materials[size_t(index)].emissiveTexture;
  std::string where = item("materials", index) + ".emissiveTexture";
  if (!readsSharedUvs(index, info.texCoord, info.extensions, where)) return;
  converted.glowTexture = texture(info.index, Encoding::Srgb, where);
  converted.glow = emissive;
}

// The normal map of glTF material `index`.
void MaterialTable::addNormalMap(int index, Material& converted) {
  const tinygltf::NormalTextureInfo& info = context_.model().materials[size_t(index)].normalTexture;
  if (info.index < 0) return;
  std::string where = item("materials", index) + ".normalTexture";
  if (!readsSharedUvs(index, info.texCoord, info.extensions, where)) return;
  double scale = finiteNumber(context_, info.scale, where + ".scale");
  converted.normalTexture = texture(info.index, Encoding::Linear, where);
  converted.normalScale = static_cast<float>(std::clamp(scale, -1e3, 1e3));
}

// KHR_materials_transmission's transmissionTexture of glTF material `index`
// (a textureInfo inside the extension: index, texCoord, extensions), for the
// kernels to read texel by texel (its red channel times the factor).
void MaterialTable::addTransmissionTexture(int index, Material& converted) {
  const tinygltf::ExtensionMap& extensions = context_.model().materials[size_t(index)].extensions;
  if (!hasExtension(extensions, "KHR_materials_transmission", "transmissionTexture")) return;
  std::string where =
      item("materials", index) + ".extensions.KHR_materials_transmission.transmissionTexture";
  const tinygltf::Value& info =
      extensions.at("KHR_materials_transmission").Get("transmissionTexture");
  auto integer = [&](const char* key, int fallback) {
    if (!info.Has(key)) return fallback;
    if (!info.Get(key).IsInt()) context_.fail(where + "." + key, "expected an integer");
    return info.Get(key).GetNumberAsInt();
  };
  if (!info.IsObject()) context_.fail(where, "expected an object");
  int texture = integer("index", -1);
  if (texture < 0) context_.fail(where + ".index", "missing or negative");
  tinygltf::ExtensionMap infoExtensions;
  if (info.Has("extensions") && info.Get("extensions").IsObject()) {
    const tinygltf::Value& nested = info.Get("extensions");
    for (const std::string& key : nested.Keys()) infoExtensions[key] = nested.Get(key);
  }
  if (converted.transmission <= 0.0f) return;  // nothing to modulate
  if (!readsSharedUvs(index, integer("texCoord", 0), infoExtensions, where)) return;
  converted.transmissionTexture = this->texture(texture, Encoding::Linear, where);
}

// The metallic-roughness texture of glTF material `index`, for the kernels
// to read texel by texel (the material's terms stay those of its mean).
void MaterialTable::addMetalRoughTexture(int index, Material& converted) {
  const tinygltf::PbrMetallicRoughness& pbr =
      context_.model().materials[size_t(index)].pbrMetallicRoughness;
  const tinygltf::TextureInfo& info = pbr.metallicRoughnessTexture;
  if (info.index < 0) return;
  std::string where = item("materials", index) + ".pbrMetallicRoughness.metallicRoughnessTexture";
  if (!readsSharedUvs(index, info.texCoord, info.extensions, where)) return;
  converted.metalRoughTexture = texture(info.index, Encoding::Linear, where);
  // The factors as convertMaterial read them (validated there).
  converted.metallic = static_cast<float>(std::clamp(pbr.metallicFactor, 0.0, 1.0));
  converted.roughness = static_cast<float>(std::clamp(pbr.roughnessFactor, 0.0, 1.0));
}

int MaterialTable::imageOf(int textureIndex, const std::string& where) {
  const auto& textures = context_.model().textures;
  if (textureIndex < 0 || size_t(textureIndex) >= textures.size()) {
    context_.fail(where, "texture " + std::to_string(textureIndex) +
                             " does not exist (the file has " + std::to_string(textures.size()) +
                             ")");
  }
  int image = textures[size_t(textureIndex)].source;
  if (image < 0) {
    // The image is only given through an extension (KTX2, WebP, ...).
    context_.warn(where, "texture " + std::to_string(textureIndex) +
                             " has no PNG or JPEG image; it is not used");
    return -1;
  }
  const auto& images = context_.model().images;
  if (size_t(image) >= images.size()) {
    context_.fail(where, "image " + std::to_string(image) + " does not exist (the file has " +
                             std::to_string(images.size()) + ")");
  }
  return image;
}

int32_t MaterialTable::texture(int textureIndex, Encoding encoding, const std::string& where) {
  int image = imageOf(textureIndex, where);
  return image < 0 ? -1 : decodeImage(image, encoding, samplingOf(textureIndex, where), where);
}

// Mean metallic (blue) and roughness (green) of a metallic-roughness texture,
// (1, 1) without one.
glm::vec2 MaterialTable::metallicRoughnessAverage(const tinygltf::TextureInfo& info,
                                                  const std::string& where) {
  if (info.index < 0) return glm::vec2(1.0f);
  int image = imageOf(info.index, where);
  if (image < 0) return glm::vec2(1.0f);
  if (auto found = averages_.find(image); found != averages_.end()) return found->second;
  std::string source;
  ImageRgba8 decoded = readImage(image, where, source);
  double metallic = 0.0, roughness = 0.0;
  size_t pixels = decoded.rgba.size() / 4;
  for (size_t i = 0; i < pixels; ++i) {
    roughness += decoded.rgba[4 * i + 1];
    metallic += decoded.rgba[4 * i + 2];
  }
  glm::vec2 mean(1.0f);
  if (pixels > 0) mean = glm::vec2(glm::dvec2(metallic, roughness) / (255.0 * double(pixels)));
  averages_.emplace(image, mean);
  return mean;
}

// glTF texture `textureIndex`'s sampler (none: repeat, bilinear). Mipmaps
// are not made, so only the magnification filter counts.
TextureSampling MaterialTable::samplingOf(int textureIndex, const std::string& where) {
  int index = context_.model().textures[size_t(textureIndex)].sampler;
  if (index < 0) return {};
  const auto& samplers = context_.model().samplers;
  if (size_t(index) >= samplers.size()) {
    context_.fail(where, "sampler " + std::to_string(index) + " does not exist (the file has " +
                             std::to_string(samplers.size()) + ")");
  }
  const tinygltf::Sampler& sampler = samplers[size_t(index)];
  std::string name = item("samplers", index);
  TextureSampling sampling;
  sampling.wrapU = wrapMode(context_, sampler.wrapS, name + ".wrapS");
  sampling.wrapV = wrapMode(context_, sampler.wrapT, name + ".wrapT");
  sampling.nearest = sampler.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
  return sampling;
}

int32_t MaterialTable::decodeImage(int index, Encoding encoding, TextureSampling sampling,
                                   const std::string& where) {
  std::tuple<int, Encoding, TextureSampling> key{index, encoding, sampling};
  if (auto found = images_.find(key); found != images_.end()) return found->second;
  Texture texture;
  auto sameImage = std::find_if(images_.begin(), images_.end(), [&](const auto& entry) {
    return std::get<0>(entry.first) == index;
  });
  if (sameImage != images_.end()) {
    // The image read before with another encoding or sampler: a copy, not a
    // second decode (the copy's memory counts against the budget all the same).
    const Texture& decoded = scene_.textures[size_t(sameImage->second)];
    texture.image = decoded.image;
    texture.source = decoded.source;
    countDecodedBytes(texture.image, index, where);
  } else {
    texture.image = readImage(index, where, texture.source);
  }
  texture.linear = encoding == Encoding::Linear;
  texture.sampling = sampling;
  scene_.textures.push_back(std::move(texture));
  int32_t added = static_cast<int32_t>(scene_.textures.size() - 1);
  images_.emplace(key, added);
  return added;
}

// Decodes image `index` (embedded bytes, or a file next to the glTF file);
// `source` says where it came from.
ImageRgba8 MaterialTable::decodeImageData(int index, const std::string& where,
                                          std::string& source) {
  const tinygltf::Image& image = context_.model().images[size_t(index)];
  std::string name = item("images", index);
  if (image.image.empty() && image.uri.empty()) context_.fail(where, name + " has no data");
  try {
    if (!image.image.empty()) {
      source = context_.fileName() + ":" + name;
      return decodeImageRgba8(image.image.data(), image.image.size(), source);
    }
    fs::path path = baseDir_ / percentDecoded(image.uri);
    source = path.string();
    std::vector<unsigned char> bytes;
    if (std::string problem = readFileBytes(path, bytes); !problem.empty()) {
      throw Error(source + ": " + problem);
    }
    return decodeImageRgba8(bytes.data(), bytes.size(), source);
  } catch (const Error& error) {
    context_.fail(where, name + ": " + error.what());
  }
}

// Every decode counts, kept or not: the budget bounds memory and time.
ImageRgba8 MaterialTable::readImage(int index, const std::string& where, std::string& source) {
  ImageRgba8 image = decodeImageData(index, where, source);
  countDecodedBytes(image, index, where);
  return image;
}

void MaterialTable::countDecodedBytes(const ImageRgba8& image, int index,
                                      const std::string& where) {
  decodedBytes_ += image.rgba.size();
  if (decodedBytes_ > kMaxTextureBytes) {
    context_.fail(where, item("images", index) + ": the decoded images exceed " +
                             std::to_string(kMaxTextureBytes >> 20) + " MiB");
  }
}

}  // namespace rt::gltf
