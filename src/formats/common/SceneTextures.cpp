#include "formats/common/SceneTextures.hpp"

#include <algorithm>
#include <array>
#include <string>
#include <system_error>

#include "util/Error.hpp"

namespace rt {
namespace {

constexpr const char* kMissingTextureName = "missing texture";
constexpr const char* kCheckerboardName = "checkerboard";

std::optional<int32_t> findTexture(const Scene& scene, const std::string& source) {
  for (size_t i = 0; i < scene.textures.size(); ++i) {
    if (scene.textures[i].source == source) return static_cast<int32_t>(i);
  }
  return std::nullopt;
}

// `count` x `count` squares of 8 x 8 texels, alternating `even` and `odd` (sRGB).
ImageRgba8 squares(std::array<uint8_t, 3> even, std::array<uint8_t, 3> odd, uint32_t count = 8) {
  constexpr uint32_t kSquare = 8;
  const uint32_t kSide = kSquare * count;
  ImageRgba8 image;
  image.width = image.height = kSide;
  image.rgba.resize(size_t{kSide} * kSide * 4);
  for (uint32_t y = 0; y < kSide; ++y) {
    for (uint32_t x = 0; x < kSide; ++x) {
      const std::array<uint8_t, 3>& colour = ((x / kSquare + y / kSquare) % 2) ? odd : even;
      uint8_t* pixel = &image.rgba[(size_t{y} * kSide + x) * 4];
      pixel[0] = colour[0];
      pixel[1] = colour[1];
      pixel[2] = colour[2];
      pixel[3] = 255;
    }
  }
  return image;
}

int32_t addGenerated(Scene& scene, const char* name, ImageRgba8 (*make)()) {
  if (const std::optional<int32_t> found = findTexture(scene, name)) return *found;
  scene.textures.push_back({name, make()});
  return static_cast<int32_t>(scene.textures.size() - 1);
}

}  // namespace

int32_t addTextureFile(Scene& scene, const std::filesystem::path& file) {
  if (const std::optional<int32_t> found = findTexture(scene, file.string())) return *found;
  scene.textures.push_back({file.string(), readImageRgba8(file)});
  return static_cast<int32_t>(scene.textures.size() - 1);
}

bool useDiffuseTextureFile(Scene& scene, Material& material,
                           const std::optional<std::filesystem::path>& file) {
  std::error_code ignored;
  if (!file || !std::filesystem::is_regular_file(*file, ignored)) {
    material.diffuseTexture = addMissingTexture(scene);
    return false;
  }
  material.texture = *file;
  try {
    material.diffuseTexture = addTextureFile(scene, *file);
  } catch (const Error& error) {
    throw Error(std::string("cannot use texture: ") + error.what());
  }
  return true;
}

int32_t addMissingTexture(Scene& scene) {
  return addGenerated(scene, kMissingTextureName, [] { return squares({255, 0, 255}, {0, 0, 0}); });
}

int32_t addCheckerTexture(Scene& scene, glm::vec3 even, glm::vec3 odd, uint32_t count) {
  // Stored as an sRGB image file stores the linear colour.
  ToneMapping srgbBytes;
  srgbBytes.srgbEncode = true;
  const auto srgb = [&](glm::vec3 linear) {
    return std::array<uint8_t, 3>{displayByte(linear.x, srgbBytes),
                                  displayByte(linear.y, srgbBytes),
                                  displayByte(linear.z, srgbBytes)};
  };
  const std::string name = "checker " + std::to_string(count);
  scene.textures.push_back({name, squares(srgb(even), srgb(odd), std::clamp(count, 1u, 64u))});
  return static_cast<int32_t>(scene.textures.size() - 1);
}

int32_t addCheckerboard(Scene& scene) {
  return addGenerated(scene, kCheckerboardName, [] {
    return squares({32, 32, 32}, {255, 255, 255});
  });
}

}  // namespace rt
