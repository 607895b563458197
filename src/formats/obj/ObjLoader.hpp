// Wavefront OBJ meshes and their .mtl materials, read with Debian's
// tinyobjloader: positions, texture coordinates and normals, polygons
// (triangulated), negative (relative) indices, groups and objects. Faces are
// gathered into one mesh per material they use. MTL materials become the
// renderer's Blinn-Phong Material:
//   Kd -> diffuse colour (kd 1); map_Kd -> texture, times Kd
//   Ks -> specular colour (ks 1 unless Ks is black); Ns -> specular exponent
//   d < 1 (or Tr > 0) -> transmission 1 - d; Ni -> index of refraction
// Faces without a material get the default grey. A material library or a
// texture that is not there is a warning (the default grey, the missing-
// texture squares of formats/common/SceneTextures.hpp); malformed files are
// one-line errors "<file>: <what>".
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <string_view>

#include "scene/Scene.hpp"

namespace rt {

// The file's meshes as shapes placed by `placement`, with their materials,
// textures and warnings; nothing else of `Scene` is set.
Scene loadObjPart(const std::filesystem::path& file, const WorldTransform& placement);

// The same from memory: `mtl` is the text of its material library ("" for
// none); textures are looked for beside `file`.
Scene parseObjPart(std::string_view obj, std::string_view mtl, const std::filesystem::path& file,
                   const WorldTransform& placement);

// An OBJ file on its own, framed like a glTF file without a camera (see
// formats/common/ModelFraming.hpp): grey background, textbook conventions
// (physical when its materials glow, Ke).
Scene loadObjScene(const std::filesystem::path& file);

bool isObjFile(const std::filesystem::path& file);

}  // namespace rt
