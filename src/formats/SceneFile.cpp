#include "formats/SceneFile.hpp"

#include <algorithm>
#include <cctype>
#include <string>

#include "formats/gltf/GltfLoader.hpp"
#include "formats/json/JsonSceneLoader.hpp"
#include "formats/obj/ObjLoader.hpp"
#include "util/Error.hpp"
#include "util/Text.hpp"

namespace rt {

bool isGltfFile(const std::filesystem::path& file) { return hasExtension(file, {".gltf", ".glb"}); }

Scene loadSceneFile(const std::filesystem::path& file, const SceneLoadOptions& options) {
  Scene scene = isGltfFile(file)  ? loadGltfScene(file)
                : isObjFile(file) ? loadObjScene(file)
                                  : loadJsonScene(file);
  if (options.strict && !scene.warnings.empty()) {
    throw Error(scene.warnings.front() + " (--strict: every warning is an error)");
  }
  return scene;
}

const char* sceneFileKind(const std::filesystem::path& file) {
  if (isGltfFile(file)) return "glTF";
  if (isObjFile(file)) return "OBJ";
  return "coursework JSON";
}

}  // namespace rt
