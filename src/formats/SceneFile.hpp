// Any scene file the renderer reads, chosen by extension: .gltf/.glb as a
// glTF scene of its own, everything else as a coursework JSON scene.
#pragma once

#include <filesystem>

#include "scene/Scene.hpp"

namespace rt {

Scene loadSceneFile(const std::filesystem::path& file);

bool isGltfFile(const std::filesystem::path& file);

}  // namespace rt
