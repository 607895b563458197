// Reads glTF 2.0 (.gltf with external or data-URI buffers, and .glb) into the
// host scene. Geometry: every triangle-based primitive of the default scene
// (or scene 0; every root node when the file has no scene), each glTF
// (mesh, primitive) stored once in Scene::meshes and placed by a MeshInstance
// per node (and per EXT_mesh_gpu_instancing instance); mirroring placements
// use a copy with reversed winding, so that winding normals keep facing out.
// Accessors: any stride, sparse, normalized integers, KHR_mesh_quantization.
// Materials map metallic-roughness onto Blinn-Phong (formulas in
// GltfMaterial.cpp); base colour textures go to Scene::textures, with
// texCoord and KHR_texture_transform applied to TriangleMesh::uvs. What cannot
// be shown (points, lines, skins, morph targets, emission, normal maps, ...)
// is listed in Scene::warnings, one line per kind.
//
// Every failure throws rt::Error with ONE line "<file>: <glTF object>: <what>",
// e.g. "box.gltf: meshes[0].primitives[1].attributes.POSITION: accessor 7 reads
// past the end of buffer view 2 (...)". All offsets, strides, counts and
// indices are checked against the real buffer sizes before reading, node
// hierarchies must be trees (cycles and shared children are errors), only
// regular files are read, and the memory a file can make the loader allocate
// is bounded by its buffer sizes (GltfContext.hpp).
#pragma once

#include <filesystem>
#include <glm/glm.hpp>

#include "scene/Scene.hpp"

namespace rt {

// A glTF file as a scene of its own (family Rendering: lights without
// falloff, unit scale; background a neutral grey 0.5).
// Camera: the first perspective camera met in a depth-first walk of the
// scene's nodes (yfov -> fovYDegrees, height 600 and width 600 * aspectRatio,
// else 800x600; position and axes from the node: forward -Z, up +Y). Without
// one, a default camera (fov 45, 800x600) looks at the centre of the
// geometry's bounding sphere from above the +z side (direction (0, 0.5, 1))
// and far enough for the sphere to fit.
// Lights: KHR_lights_punctual, normalised so that the brightest light's
// strongest channel is 1 (colour * intensity / max over lights); spot lights
// become point lights, directional lights point lights 100 bounding radii
// away against their direction (both with a warning). Without lights, one
// white light of intensity 1 sits above and to the right of the camera:
// at camera + d (0.5 up + 0.5 right), d = the camera's distance to the centre.
Scene loadGltfScene(const std::filesystem::path& file);

// Adds the file's meshes, materials, textures, mesh instances and punctual
// lights (normalised as above) to `scene`, every node transform premultiplied
// by `placement`; warnings are appended. Camera, family and background of
// `scene` are left alone; a file that fails leaves `scene` unchanged. Used
// for glTF models inside JSON scenes.
void appendGltf(Scene& scene, const std::filesystem::path& file, const WorldTransform& placement);

}  // namespace rt
