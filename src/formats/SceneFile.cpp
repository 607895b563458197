#include "formats/SceneFile.hpp"

#include <algorithm>
#include <cctype>
#include <string>

#include "formats/gltf/GltfLoader.hpp"
#include "formats/json/JsonSceneLoader.hpp"
#include "formats/obj/ObjLoader.hpp"
#include "formats/ply/PlyLoader.hpp"
#include "util/Error.hpp"
#include "util/Text.hpp"

namespace rt {

bool isGltfFile(const std::filesystem::path& file) { return hasExtension(file, {".gltf", ".glb"}); }

Scene loadSceneFile(const std::filesystem::path& file, const SceneLoadOptions& options) {
  Scene scene = isGltfFile(file)  ? loadGltfScene(file)
                : isObjFile(file) ? loadObjScene(file)
                : isPlyFile(file) ? loadPlyScene(file)
                                  : loadJsonScene(file);
  if (scene.fileKind.empty()) {
    scene.fileKind = isGltfFile(file)  ? "glTF"
                     : isObjFile(file) ? "OBJ"
                     : isPlyFile(file) ? "PLY"
                                       : "coursework JSON";
  }
  if (options.strict && !scene.warnings.empty()) {
    throw Error(scene.warnings.front() + " (--strict: every warning is an error)");
  }
  return scene;
}

}  // namespace rt
