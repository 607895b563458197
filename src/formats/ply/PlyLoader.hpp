// Reads Stanford PLY triangle meshes (ASCII, binary little and big endian).
//
// What is read: the `vertex` element's x, y, z (any scalar type), optional
// normals nx, ny, nz, texture coordinates (u, v), (s, t), (texture_u,
// texture_v) or (texture_s, texture_t), and colours (red, green, blue), (r, g,
// b) or (diffuse_red, diffuse_green, diffuse_blue), sRGB-encoded, integers
// over their type's range; the `face` element's `vertex_indices`
// (or `vertex_index`) lists, fanned into triangles, and their `texcoord`
// lists (MeshLab's per-corner u, v; vertices are split along the seams); a
// `tristrips` element (-1 restarts a strip); `comment TextureFile NAME`.
// Other properties and elements are skipped; elements may come in any order.
//
// What is rejected, with an rt::Error whose one line reads
// "<file>: byte <offset>: <what is wrong>": anything that is not a mesh
// (point clouds, range scans, empty files), truncated or trailing data, counts
// the file cannot hold, list lengths below 3 or beyond the file, vertex indices
// out of range, non-finite coordinates, normals or UVs. Declared counts are
// checked against the file size before anything is allocated, so a hostile
// header costs no memory; memory stays proportional to the file size.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "scene/Scene.hpp"

namespace rt {

// A PLY file's mesh and the images its header names (`comment TextureFile`).
struct PlyModel {
  TriangleMesh mesh;
  std::vector<std::string> textureFiles;
};

// Loads a PLY file. Unreadable files fail with "<file>: cannot open: <reason>".
PlyModel loadPlyModel(const std::filesystem::path& file);
// Its mesh alone (a mesh of a JSON scene, whose material decides its texture).
TriangleMesh loadPly(const std::filesystem::path& file);

// Same from bytes in memory; `name` only starts the error messages.
TriangleMesh parsePly(std::string_view bytes, std::string_view name);

// A PLY file on its own (`raytracer bunny.ply out.png`): its mesh in the
// default grey material, textured by its first TextureFile where it has
// texture coordinates, framed like an OBJ or glTF file without a camera
// (formats/common/ModelFraming.hpp).
Scene loadPlyScene(const std::filesystem::path& file);

bool isPlyFile(const std::filesystem::path& file);

}  // namespace rt
