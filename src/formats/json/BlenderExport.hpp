// Scenes exported from Blender by a later coursework's students ("ASCII
// scene" files): each student wrote their own exporter, so the same things
// come in many layouts (README "Student scenes" lists them). They are read
// into rt::Scene in Blender's own units: the physical conventions, light
// power in watts, Blender's camera, cube, plane and cylinder primitives.
#pragma once

#include <filesystem>

#include "formats/common/Diagnostics.hpp"
#include "formats/json/JsonReader.hpp"
#include "scene/Scene.hpp"

namespace rt {

// True for the layouts of Blender exports (`properties.cameras[]`,
// `cameras[]` beside `cubes`, a `camera` with `location` and a gaze,
// `objects` or a bare list of Blender objects with a "CAMERA", objects
// grouped by Blender type `CAMERA`/`MESH`/`LIGHT`), never for a coursework
// JSON scene.
bool looksLikeBlenderExport(const Json& document);

// Reads a document looksLikeBlenderExport accepted; errors and warnings go
// through `diagnostics` like the coursework reader's.
Scene readBlenderExport(const Json& document, const std::filesystem::path& file,
                        Diagnostics& diagnostics);

}  // namespace rt
