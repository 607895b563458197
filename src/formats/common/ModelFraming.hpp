// What a model file on its own (glTF, OBJ, PLY) needs to become a scene: a camera
// that frames its geometry and a light when the file brings none, and the
// merge of one file's content into a scene (models inside JSON scenes).
#pragma once

#include <glm/glm.hpp>
#include <optional>

#include "scene/Scene.hpp"
#include "scene/SceneBounds.hpp"

namespace rt {

// The grey every model scene is drawn on.
constexpr float kModelBackgroundGrey = 0.5f;

// A model file kind: its name for `raytracer check` ("an OBJ file") and what
// its materials glow by ("Ke"; nullptr where they cannot glow).
struct ModelKind {
  const char* name;
  const char* glowKey = nullptr;
};

// Makes `scene`, a model file's content, a scene of its own: the grey
// background; `camera`, else one looking at `bounds` (fov 45, 800x600, from
// the +z side where the bounding sphere fits: from above, or straight on
// where the model glows); a white light of
// intensity 1 above and right of the camera when the model brings no light
// (point or glowing); and textbook conventions, or physical where its
// materials glow: an emitted radiance needs the physical falloff and units
// (the textbook's unit lights do not fall off).
void frameModel(Scene& scene, const WorldBounds& bounds, const std::optional<Camera>& camera,
                const ModelKind& kind);

// The same around the model's mesh vertices, for files without cameras
// (OBJ, PLY).
void frameModelScene(Scene& scene, const ModelKind& kind);

// Appends `part`'s materials, textures, meshes, shapes, lights (point and
// area) and warnings to `scene`, shifting the indices that point into its
// lists.
void appendScenePart(Scene& scene, Scene&& part);

}  // namespace rt
