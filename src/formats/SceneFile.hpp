// Any scene file the renderer reads, chosen by extension: .gltf/.glb as a
// glTF scene of its own, .obj as an OBJ model (framed the same way),
// everything else as a JSON scene (coursework, or a Blender export).
#pragma once

#include <filesystem>

#include "scene/Scene.hpp"

namespace rt {

struct SceneLoadOptions {
  // Lenient by default: what a loader can read around (a missing texture or
  // mesh file, a missing key with an obvious default, an unknown key) is a
  // warning in Scene::warnings. Strict: the first such warning is the error.
  bool strict = false;
};

Scene loadSceneFile(const std::filesystem::path& file, const SceneLoadOptions& options = {});

bool isGltfFile(const std::filesystem::path& file);

}  // namespace rt
