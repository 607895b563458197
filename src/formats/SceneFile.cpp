#include "formats/SceneFile.hpp"

#include <algorithm>
#include <cctype>
#include <string>

#include "formats/gltf/GltfLoader.hpp"
#include "formats/json/JsonSceneLoader.hpp"

namespace rt {

bool isGltfFile(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".gltf" || ext == ".glb";
}

Scene loadSceneFile(const std::filesystem::path& file) {
  return isGltfFile(file) ? loadGltfScene(file) : loadJsonScene(file);
}

}  // namespace rt
