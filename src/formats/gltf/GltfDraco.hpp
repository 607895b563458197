// KHR_draco_mesh_compression: primitives whose attributes and indices are
// stored as one Draco-compressed buffer view, decoded with Google's Draco
// library (Debian's libdraco) into plain accessors, so that the rest of the
// loader reads them as it reads any other.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "formats/gltf/GltfTiny.hpp"

namespace rt::gltf {

// Decodes every compressed triangle primitive of `model` in place: each
// attribute the extension names gets a new FLOAT accessor over a new buffer
// holding its decoded values (one per Draco point), and the primitive gets a
// new UNSIGNED_INT index accessor over the decoded triangles, in TRIANGLES
// mode. Primitives that several meshes share decode once per buffer view.
// Points and lines are left as they are (the loader skips them). Throws
// rt::Error "<file>: meshes[m].primitives[p].extensions.KHR_draco_mesh_compression...: <what>"
// for a buffer view or attribute that does not exist, data that does not
// decode, or decoded data larger than the file can justify.
// The document's JSON text with the "indices" of every compressed primitive
// removed, or nothing when no primitive has them (or the text is no JSON
// object). Such an index accessor has no buffer view until Draco fills it,
// which tinygltf refuses; decodeDracoPrimitives gives every compressed
// primitive its indices back. Run after the JSON's depth and size checks.
std::optional<std::string> jsonWithoutDracoIndices(std::string_view json);

void decodeDracoPrimitives(tinygltf::Model& model, const std::string& fileName);

}  // namespace rt::gltf
