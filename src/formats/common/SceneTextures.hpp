// The textures of a scene's materials, as every loader adds them: each file
// decoded once however many materials use it, and the stand-ins drawn where
// a file names a texture that is not there or a procedural one.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>

#include "scene/Scene.hpp"

namespace rt {

// Index of `file` in scene.textures, decoding it on first use. Throws
// rt::Error (the image reader's message) when it cannot be decoded.
int32_t addTextureFile(Scene& scene, const std::filesystem::path& file);

// The stand-in for a texture file that is not there: magenta and black
// squares, 8 x 8 over the unit square, that no real texture looks like (README
// "Student scenes").
int32_t addMissingTexture(Scene& scene);

// Puts the image `file` on `material` as its diffuse texture and returns true.
// Where there is no such file (or none was found), it puts the missing-texture
// squares there and returns false: the caller warns in its own words and names
// the texture as written. Throws rt::Error "cannot use texture: <reason>" when
// the file does not decode.
bool useDiffuseTextureFile(Scene& scene, Material& material,
                           const std::optional<std::filesystem::path>& file);

// TsFreddie's procedural "checkerboard": 8 x 8 light and dark grey squares.
int32_t addCheckerboard(Scene& scene);

// A checker of `squares` x `squares` squares over the unit square in two
// linear colours (a procedural texture some students' files describe).
int32_t addCheckerTexture(Scene& scene, glm::vec3 even, glm::vec3 odd, uint32_t squares);

}  // namespace rt
