// Tests for KHR_draco_mesh_compression in rt::loadGltfScene: meshes that the
// test compresses itself with Draco's encoder (losslessly, so that every
// decoded value can be compared), in .gltf and .glb files, and compressed
// primitives broken in each way the loader checks. The Khronos samples'
// Draco variants are compared with their uncompressed twins in
// test_gltf_loader.cpp.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

// The includes must stay between the two (clang-format would sort them).
// clang-format off
#include "util/ThirdPartyBegin.hpp"
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include "util/ThirdPartyEnd.hpp"
// clang-format on

#include "formats/gltf/GltfLoader.hpp"
#include "support/Glb.hpp"
#include "util/Error.hpp"

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

// A unit quad of two triangles in z = 0, with a normal, texture coordinates
// and an 8-bit colour at each corner.
struct Corner {
  glm::vec3 position;
  glm::vec2 uv;
  glm::u8vec3 color;
};
const std::vector<Corner> kCorners = {{{0, 0, 0}, {0, 0}, {255, 0, 0}},
                                      {{1, 0, 0}, {1, 0}, {0, 255, 0}},
                                      {{1, 1, 0}, {1, 1}, {0, 0, 255}},
                                      {{0, 1, 0}, {0, 1}, {51, 102, 153}}};
const std::vector<glm::uvec3> kFaces = {{0, 1, 2}, {0, 2, 3}};

// The Draco stream of the quad and its attributes' unique ids.
struct Compressed {
  std::vector<uint8_t> bytes;
  int position = -1, normal = -1, uv = -1, color = -1;
};

Compressed compressQuad() {
  draco::TriangleSoupMeshBuilder builder;
  builder.Start(int(kFaces.size()));
  int position = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  int normal = builder.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
  int uv = builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
  int color = builder.AddAttribute(draco::GeometryAttribute::COLOR, 3, draco::DT_UINT8);
  const glm::vec3 up(0, 0, 1);
  for (size_t f = 0; f < kFaces.size(); ++f) {
    const Corner& a = kCorners[kFaces[f].x];
    const Corner& b = kCorners[kFaces[f].y];
    const Corner& c = kCorners[kFaces[f].z];
    const draco::FaceIndex face{uint32_t(f)};
    builder.SetAttributeValuesForFace(position, face, &a.position, &b.position, &c.position);
    builder.SetAttributeValuesForFace(normal, face, &up, &up, &up);
    builder.SetAttributeValuesForFace(uv, face, &a.uv, &b.uv, &c.uv);
    builder.SetAttributeValuesForFace(color, face, &a.color, &b.color, &c.color);
  }
  std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
  REQUIRE(mesh);
  draco::Encoder encoder;  // no quantization: float attributes are kept exactly
  encoder.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);
  draco::EncoderBuffer stream;
  REQUIRE(encoder.EncodeMeshToBuffer(*mesh, &stream).ok());
  Compressed out;
  out.bytes.assign(stream.data(), stream.data() + stream.size());
  out.position = int(mesh->attribute(position)->unique_id());
  out.normal = int(mesh->attribute(normal)->unique_id());
  out.uv = int(mesh->attribute(uv)->unique_id());
  out.color = int(mesh->attribute(color)->unique_id());
  return out;
}

// A glTF document of the quad as one compressed primitive: its accessors
// have no buffer view (Draco fills them) and the stream is buffer view 0.
Json quadDocument(const Compressed& quad) {
  auto accessor = [](int componentType, const char* type, bool normalized = false) {
    return Json{
        {"componentType", componentType}, {"count", 4}, {"type", type}, {"normalized", normalized}};
  };
  Json extension = {{"bufferView", 0},
                    {"attributes",
                     {{"POSITION", quad.position},
                      {"NORMAL", quad.normal},
                      {"TEXCOORD_0", quad.uv},
                      {"COLOR_0", quad.color}}}};
  Json primitive = {
      {"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}, {"COLOR_0", 3}}},
      {"indices", 4},
      {"extensions", {{"KHR_draco_mesh_compression", extension}}}};
  return {{"asset", {{"version", "2.0"}}},
          {"extensionsUsed", {"KHR_draco_mesh_compression"}},
          {"extensionsRequired", {"KHR_draco_mesh_compression"}},
          {"scene", 0},
          {"scenes", {{{"nodes", {0}}}}},
          {"nodes", {{{"mesh", 0}}}},
          {"meshes", {{{"primitives", {primitive}}}}},
          {"accessors",
           {accessor(5126, "VEC3"),
            accessor(5126, "VEC3"),
            accessor(5126, "VEC2"),
            accessor(5121, "VEC3", true),
            {{"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}},
          {"bufferViews", {{{"buffer", 0}, {"byteLength", quad.bytes.size()}}}}};
}

fs::path scratchDir() {
  fs::path dir = fs::path(RT_TEST_OUTPUT_DIR) / "gltf-draco";
  fs::create_directories(dir);
  return dir;
}

// NAME.gltf and NAME.bin (the stream) in the scratch folder.
fs::path writeGltf(const std::string& name, Json doc, const std::vector<uint8_t>& bin) {
  doc["buffers"] = {{{"byteLength", bin.size()}, {"uri", name + ".bin"}}};
  std::ofstream(scratchDir() / (name + ".bin"), std::ios::binary)
      .write(reinterpret_cast<const char*>(bin.data()), std::streamsize(bin.size()));
  fs::path file = scratchDir() / (name + ".gltf");
  std::ofstream(file) << doc.dump(2);
  return file;
}

// NAME.glb: the document and the stream in one file.
fs::path writeGlb(const std::string& name, const Json& doc, const std::vector<uint8_t>& bin) {
  fs::path file = scratchDir() / (name + ".glb");
  std::ofstream(file, std::ios::binary) << rt::test::glbBytes(doc, bin);
  return file;
}

std::string errorOf(const fs::path& file) {
  try {
    rt::loadGltfScene(file);
  } catch (const rt::Error& error) {
    return error.what();
  }
  return "(loaded)";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Checks the decoded quad: every decoded vertex is one of the corners, with
// that corner's normal, texture coordinates and colour, and the two faces
// cover the four corners with the file's winding.
void checkQuad(const rt::Scene& scene) {
  REQUIRE(scene.meshes.size() == 1);
  const rt::TriangleMesh& mesh = scene.meshes[0];
  REQUIRE(mesh.faces.size() == 2);
  REQUIRE(mesh.normals.size() == mesh.positions.size());
  REQUIRE(mesh.uvs.size() == mesh.positions.size());
  REQUIRE(mesh.colors.size() == mesh.positions.size());
  std::vector<bool> seen(kCorners.size(), false);
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    size_t corner = 0;
    while (corner < kCorners.size() && kCorners[corner].position != mesh.positions[v]) ++corner;
    REQUIRE_MESSAGE(corner < kCorners.size(), "vertex " << v << " is no corner of the quad");
    seen[corner] = true;
    CHECK(mesh.normals[v] == glm::vec3(0, 0, 1));
    CHECK(mesh.uvs[v] == kCorners[corner].uv);
    glm::vec3 expected = glm::vec3(kCorners[corner].color) / 255.0f;  // glTF colours are linear
    CHECK(glm::length(mesh.colors[v] - expected) < 1e-6f);
  }
  CHECK(std::count(seen.begin(), seen.end(), true) == 4);
  for (const glm::uvec3& face : mesh.faces) {
    glm::vec3 a = mesh.positions[face.x], b = mesh.positions[face.y], c = mesh.positions[face.z];
    CHECK(glm::cross(b - a, c - a).z > 0.0f);  // counter-clockwise seen from +z, as written
  }
}

}  // namespace

TEST_SUITE("scene gltf draco") {
  TEST_CASE("a compressed primitive decodes to its attributes, in .gltf and .glb files") {
    Compressed quad = compressQuad();
    Json doc = quadDocument(quad);
    rt::Scene scene = rt::loadGltfScene(writeGltf("quad", doc, quad.bytes));
    checkQuad(scene);
    for (const std::string& line : scene.warnings) {
      CHECK_MESSAGE(!contains(line, "KHR_draco_mesh_compression"), line);
    }
    checkQuad(rt::loadGltfScene(writeGlb("quad", doc, quad.bytes)));
  }

  TEST_CASE("without indices, and one stream shared by two meshes") {
    Compressed quad = compressQuad();
    Json doc = quadDocument(quad);
    doc["meshes"][0]["primitives"][0].erase("indices");
    checkQuad(rt::loadGltfScene(writeGltf("no-indices", doc, quad.bytes)));

    doc["meshes"].push_back(doc["meshes"][0]);
    doc["nodes"].push_back({{"mesh", 1}, {"translation", {3, 0, 0}}});
    doc["scenes"][0]["nodes"].push_back(1);
    rt::Scene twice = rt::loadGltfScene(writeGltf("shared", doc, quad.bytes));
    CHECK(twice.meshes.size() == 2);
    CHECK(twice.shapes.size() == 2);
  }

  TEST_CASE("broken compressed primitives fail with one line naming the place") {
    Compressed quad = compressQuad();
    const std::string at = "meshes[0].primitives[0].extensions.KHR_draco_mesh_compression";
    auto broken = [&](const std::string& name, auto change) {
      Json doc = quadDocument(quad);
      std::vector<uint8_t> bin = quad.bytes;
      change(doc, bin);
      std::string message = errorOf(writeGltf(name, doc, bin));
      CHECK_MESSAGE(message.find('\n') == std::string::npos, message);
      return message;
    };
    const Json::json_pointer ext("/meshes/0/primitives/0/extensions/KHR_draco_mesh_compression");
    CHECK(contains(broken("view", [&](Json& d, auto&) { d[ext]["bufferView"] = 5; }),
                   at + ".bufferView: buffer view 5 does not exist (the file has 1)"));
    CHECK(contains(broken("view-type", [&](Json& d, auto&) { d[ext]["bufferView"] = "0"; }),
                   at + ".bufferView: must be the index of a buffer view"));
    CHECK(contains(
        broken("truncated",
               [&](Json& d, auto&) { d["bufferViews"][0]["byteLength"] = quad.bytes.size() / 2; }),
        at + ".bufferView: buffer view 0 is no Draco mesh"));
    CHECK(contains(broken("garbage",
                          [&](Json&, std::vector<uint8_t>& bin) {
                            std::fill(bin.begin(), bin.end(), uint8_t(0x5A));
                          }),
                   at + ".bufferView: buffer view 0 is no Draco mesh"));
    CHECK(contains(
        broken("attribute-id", [&](Json& d, auto&) { d[ext]["attributes"]["NORMAL"] = 9; }),
        at + ".attributes.NORMAL: the Draco mesh has no attribute 9"));
    CHECK(
        contains(broken("components", [&](Json& d, auto&) { d["accessors"][2]["type"] = "VEC3"; }),
                 at + ".attributes.TEXCOORD_0: the Draco attribute has 2 components, its "
                      "accessor 2 3"));
    CHECK(contains(broken("not-in-primitive",
                          [&](Json& d, auto&) {
                            d["meshes"][0]["primitives"][0]["attributes"].erase("COLOR_0");
                          }),
                   at + ".attributes.COLOR_0: the primitive has no attribute COLOR_0"));
    // tinygltf drops an extension that is no object; the accessors then have no data.
    CHECK(contains(broken("not-object", [&](Json& d, auto&) { d[ext] = 3; }),
                   "meshes[0].primitives[0].attributes.POSITION: accessor 0 has neither a "
                   "buffer view nor sparse values"));
  }
}
