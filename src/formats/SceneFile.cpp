#include "formats/SceneFile.hpp"

#include <algorithm>
#include <cctype>
#include <string>
#include <string_view>

#include "formats/common/FileBytes.hpp"
#include "formats/gltf/GltfLoader.hpp"
#include "formats/json/JsonSceneLoader.hpp"
#include "formats/obj/ObjLoader.hpp"
#include "formats/ply/PlyLoader.hpp"
#include "util/Error.hpp"
#include "util/Text.hpp"

namespace rt {

bool isGltfFile(const std::filesystem::path& file) { return hasExtension(file, {".gltf", ".glb"}); }

namespace {

// Scene files of any other extension are read as JSON (students name them
// .txt or .scene), but only when they start as JSON does (after a UTF-8 byte
// order mark and blanks: an object or a comment): an STL or FBX model would
// otherwise fail with a JSON syntax error at byte 1 that names no reason.
Scene loadOtherSceneFile(const std::filesystem::path& file) {
  const std::string text = readFileOrThrow(file);
  if (!hasExtension(file, {".json"})) {
    std::string_view rest(text);
    if (rest.starts_with("\xEF\xBB\xBF")) rest.remove_prefix(3);
    const size_t first = rest.find_first_not_of(" \t\r\n");
    if (first != std::string_view::npos && rest[first] != '{' && rest[first] != '/') {
      throw Error(file.string() +
                  ": not a scene file: scenes are JSON (.json), glTF (.gltf, .glb), OBJ or PLY");
    }
  }
  return parseJsonScene(text, file);
}

// `scene` with `kind` as its file kind, unless its loader named a more
// precise one (a Blender export).
Scene ofKind(Scene scene, const char* kind) {
  if (scene.fileKind.empty()) scene.fileKind = kind;
  return scene;
}

// The file read by the loader its extension picks.
Scene loadByExtension(const std::filesystem::path& file) {
  if (isGltfFile(file)) return ofKind(loadGltfScene(file), "glTF");
  if (isObjFile(file)) return ofKind(loadObjScene(file), "OBJ");
  if (isPlyFile(file)) return ofKind(loadPlyScene(file), "PLY");
  return ofKind(loadOtherSceneFile(file), "coursework JSON");
}

}  // namespace

Scene loadSceneFile(const std::filesystem::path& file, const SceneLoadOptions& options) {
  Scene scene = loadByExtension(file);
  if (options.strict && !scene.warnings.empty()) {
    throw Error(scene.warnings.front() + " (--strict: every warning is an error)");
  }
  return scene;
}

}  // namespace rt
