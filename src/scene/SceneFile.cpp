#include "scene/SceneFile.hpp"

#include <algorithm>
#include <cctype>
#include <string>

#include "scene/GltfLoader.hpp"
#include "scene/SceneLoader.hpp"

namespace rt {

bool isGltfFile(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".gltf" || ext == ".glb";
}

Scene loadSceneFile(const std::filesystem::path& file) {
  return isGltfFile(file) ? loadGltfScene(file) : loadScene(file);
}

}  // namespace rt
