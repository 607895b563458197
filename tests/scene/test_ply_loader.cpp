// Tests for rt::loadPly / rt::parsePly: every file under shared/assets/ply
// (loads with known counts, or is rejected for a stated reason), and
// synthetic files for each format, type, layout and kind of corruption.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "formats/SceneFile.hpp"
#include "formats/ply/PlyLoader.hpp"
#include "io/Image.hpp"
#include "render/Renderer.hpp"
#include "support/TestSupport.hpp"
#include "util/Error.hpp"

namespace {

namespace fs = std::filesystem;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// ------------------------------------------------------- synthetic writer

struct TestProperty {
  std::string type;
  std::string name;
  std::string countType;  // empty for scalars
};

// Records are flat: a list contributes its length, then its items.
struct TestElement {
  std::string name;
  std::vector<TestProperty> properties;
  std::vector<std::vector<double>> records;
};

enum class Layout { Ascii, LittleEndian, BigEndian };

const char* formatName(Layout layout) {
  switch (layout) {
    case Layout::Ascii: return "ascii";
    case Layout::LittleEndian: return "binary_little_endian";
    case Layout::BigEndian: return "binary_big_endian";
  }
  return "";
}

template <typename T>
void appendRaw(std::string& out, T value, bool bigEndian) {
  auto raw = std::bit_cast<std::array<char, sizeof(T)>>(value);
  if (bigEndian != (std::endian::native == std::endian::big)) std::reverse(raw.begin(), raw.end());
  out.append(raw.data(), raw.size());
}

void appendBinary(std::string& out, const std::string& type, double value, bool bigEndian) {
  if (type == "char" || type == "int8") return appendRaw(out, static_cast<int8_t>(value), false);
  if (type == "uchar" || type == "uint8") return appendRaw(out, static_cast<uint8_t>(value), false);
  if (type == "short" || type == "int16")
    return appendRaw(out, static_cast<int16_t>(value), bigEndian);
  if (type == "ushort" || type == "uint16") {
    return appendRaw(out, static_cast<uint16_t>(value), bigEndian);
  }
  if (type == "int" || type == "int32")
    return appendRaw(out, static_cast<int32_t>(value), bigEndian);
  if (type == "uint" || type == "uint32") {
    return appendRaw(out, static_cast<uint32_t>(value), bigEndian);
  }
  if (type == "float" || type == "float32") {
    return appendRaw(out, static_cast<float>(value), bigEndian);
  }
  appendRaw(out, value, bigEndian);
}

bool isFloatType(const std::string& type) {
  return type == "float" || type == "float32" || type == "double" || type == "float64";
}

void appendValue(std::string& out, const std::string& type, double value, Layout layout) {
  if (layout != Layout::Ascii) return appendBinary(out, type, value, layout == Layout::BigEndian);
  if (!out.empty() && out.back() != '\n') out += ' ';
  std::array<char, 64> text;
  if (isFloatType(type)) {
    std::snprintf(text.data(), text.size(), "%.17g", value);
  } else {
    std::snprintf(text.data(), text.size(), "%lld", static_cast<long long>(value));
  }
  out += text.data();
}

std::string headerOf(const std::vector<TestElement>& elements, Layout layout,
                     const std::string& eol) {
  std::string header = "ply" + eol + "format " + formatName(layout) + " 1.0" + eol;
  for (const TestElement& element : elements) {
    header += "element " + element.name + " " + std::to_string(element.records.size()) + eol;
    for (const TestProperty& property : element.properties) {
      header += "property " +
                (property.countType.empty() ? "" : "list " + property.countType + " ") +
                property.type + " " + property.name + eol;
    }
  }
  return header + "end_header" + eol;
}

std::string bodyOf(const std::vector<TestElement>& elements, Layout layout) {
  std::string body;
  for (const TestElement& element : elements) {
    for (const std::vector<double>& record : element.records) {
      size_t next = 0;
      for (const TestProperty& property : element.properties) {
        size_t items = 1;
        if (!property.countType.empty()) {
          // Lying lengths (negative, huge) write what the record holds.
          const double length = std::max(record.at(next), 0.0);
          items = std::min(static_cast<size_t>(std::min(length, 1e9)), record.size() - next - 1);
          appendValue(body, property.countType, record.at(next++), layout);
        }
        for (size_t i = 0; i < items; ++i) {
          appendValue(body, property.type, record.at(next++), layout);
        }
      }
      if (layout == Layout::Ascii) body += '\n';
    }
  }
  return body;
}

std::string writePly(const std::vector<TestElement>& elements, Layout layout,
                     const std::string& eol = "\n") {
  return headerOf(elements, layout, eol) + bodyOf(elements, layout);
}

TestElement vertexElement(const std::vector<glm::vec3>& positions,
                          const std::string& type = "float") {
  TestElement element{"vertex", {{type, "x", ""}, {type, "y", ""}, {type, "z", ""}}, {}};
  for (const glm::vec3& p : positions) element.records.push_back({p.x, p.y, p.z});
  return element;
}

TestElement faceElement(const std::vector<std::vector<double>>& polygons,
                        const std::string& countType = "uchar",
                        const std::string& indexType = "int") {
  TestElement element{"face", {{indexType, "vertex_indices", countType}}, {}};
  for (const std::vector<double>& polygon : polygons) {
    std::vector<double> record{static_cast<double>(polygon.size())};
    record.insert(record.end(), polygon.begin(), polygon.end());
    element.records.push_back(record);
  }
  return element;
}

const std::vector<glm::vec3> kSquare = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};

// A small mesh that exercises every part of a record: kept and skipped
// scalars, normals, UVs, a skipped list, and a quad.
std::vector<TestElement> richMesh() {
  TestElement vertices{"vertex",
                       {{"float", "x", ""},
                        {"float", "y", ""},
                        {"float", "z", ""},
                        {"uchar", "red", ""},
                        {"float", "nx", ""},
                        {"float", "ny", ""},
                        {"float", "nz", ""},
                        {"float", "u", ""},
                        {"float", "v", ""}},
                       {}};
  for (const glm::vec3& p : kSquare)
    vertices.records.push_back({p.x, p.y, p.z, 7, 0, 0, 1, p.x, p.y});
  TestElement faces{"face", {{"int", "vertex_indices", "uchar"}, {"float", "weights", "int"}}, {}};
  faces.records.push_back({4, 0, 1, 2, 3, 2, 0.5, 0.25});
  faces.records.push_back({3, 0, 2, 3, 0});
  return {vertices, faces};
}

std::string plyError(std::string_view bytes, std::string_view name = "t.ply") {
  try {
    rt::parsePly(bytes, name);
  } catch (const rt::Error& error) {
    const std::string message = error.what();
    CHECK_MESSAGE(!contains(message, "\n"), "error messages are one line: " << message);
    return message;
  }
  return "";
}

// "t.ply: byte <offset of `at` in `bytes`>: "
std::string prefixAt(std::string_view bytes, std::string_view at, size_t from = 0) {
  return "t.ply: byte " + std::to_string(bytes.find(at, from)) + ": ";
}

fs::path outputDir() {
  const fs::path dir = fs::path(RT_TEST_OUTPUT_DIR) / "ply";
  fs::create_directories(dir);
  return dir;
}

fs::path writeFile(const std::string& name, const std::string& bytes) {
  const fs::path file = outputDir() / name;
  std::ofstream(file, std::ios::binary) << bytes;
  return file;
}

// ----------------------------------------------------------- shared files

fs::path plyAssets() { return rt::test::requireShared() / "assets/ply"; }

struct Expected {
  size_t vertices = 0;
  size_t triangles = 0;
  bool normals = false;
  bool uvs = false;
  std::string error;  // non-empty: the file must be rejected with this text
};

Expected loads(size_t vertices, size_t triangles, bool normals = false, bool uvs = false) {
  return {vertices, triangles, normals, uvs, ""};
}
Expected rejected(const std::string& why) { return {0, 0, false, false, why}; }

const std::string kNoFaces = "no faces: the header declares no 'face' or 'tristrips' records";

// Every file under shared/assets/ply and what must happen to it.
std::map<std::string, Expected> expectedOutcomes() {
  const std::string assimp = "edge-cases/assimp-testmodels-deb/";
  const std::string draco = "edge-cases/draco-testdata/testdata/";
  const std::string happly = "edge-cases/happly-sampledata/test/sampledata/";
  const std::string tinyply = "edge-cases/tinyply-assets/assets/";
  const std::string bunny = "stanford-bunny/bunny/";
  return {
      // Blender 2.47's banner line lacks "comment"; (s, t) UVs and normals.
      {assimp + "PLY/Wuson.ply", loads(11184, 3732, true, true)},
      {assimp + "PLY/cube.ply", loads(8, 12)},  // quads, trailing blanks in the header
      {assimp + "PLY/cube_binary.ply", loads(8, 12)},
      {assimp + "PLY/cube_uv.ply", loads(24, 12, true, true)},
      {assimp + "PLY/float-color.ply", loads(3, 1)},
      // The index list sits in the vertex element and there is no face element.
      {assimp + "PLY/issue623.ply", rejected("byte 259: " + kNoFaces)},
      {assimp + "PLY/points.ply", rejected(kNoFaces)},  // a point cloud
      {assimp + "PLY/pond.0.ply", rejected(kNoFaces)},  // a binary point cloud
      {assimp + "invalid/empty.ply", rejected("byte 0: empty file")},
      {draco + "Box.ply", loads(24, 12, true)},  // CR-only header, extra 'material' element
      {draco + "cube_att.ply", loads(24, 12, true, true)},  // per-corner texcoord lists
      {draco + "cube_quads.ply", loads(8, 12)},
      {draco + "delim_test.ply", loads(24, 12, true)},  // CR-only, first data byte is CR
      {draco + "float_inf_point_cloud.ply", rejected(kNoFaces)},
      {draco + "float_two_att_point_cloud.ply", rejected(kNoFaces)},
      {draco + "int_point_cloud.ply", rejected(kNoFaces)},
      {draco + "point_cloud_test_pos.ply", rejected(kNoFaces)},  // element face 0
      {draco + "point_cloud_test_pos_norm.ply", rejected(kNoFaces)},
      {draco + "test_extra_whitespace.ply", loads(3, 1)},
      {draco + "test_generic.ply", loads(114, 224)},
      {draco + "test_more_datatypes.ply", loads(3, 1)},
      {draco + "test_pos_color.ply", loads(114, 224)},
      {draco + "test_pos_color_ascii.ply", loads(114, 224)},
      {happly + "platonic_shelf.ply", loads(50, 80)},  // faces before vertices, polygons
      {happly + "platonic_shelf_ascii.ply", loads(50, 80)},
      {happly + "platonic_shelf_big_endian.ply", loads(50, 80)},
      // The header declares one face and the body carries two.
      {"edge-cases/rply-etc/input.ply",
       rejected("byte 259: unexpected data after face 0, the last record the header declares")},
      {tinyply + "bunny.ply", loads(35947, 69451)},
      {tinyply + "elephant.ply", loads(19753, 39290)},  // one tristrip, -1 restarts
      {tinyply + "icosahedron.ply", loads(12, 20, true)},
      {tinyply + "icosahedron_ascii.ply", loads(12, 20, true)},
      // MeshLab's per-corner texcoord lists: 12103 vertices, split along the seams.
      {tinyply + "sofa.ply", loads(13347, 24104, false, true)},
      {tinyply + "sofa_ascii.ply", loads(12103, 24104)},
      // Raw range scans: a range_grid element, no faces.
      {bunny + "data/bun000.ply", rejected("byte 605: " + kNoFaces)},
      {bunny + "data/bun045.ply", rejected("byte 605: " + kNoFaces)},
      {bunny + "reconstruction/bun_zipper.ply", loads(35947, 69451)},
      {bunny + "reconstruction/bun_zipper_res2.ply", loads(8171, 16301)},
      {bunny + "reconstruction/bun_zipper_res3.ply", loads(1889, 3851)},
      {bunny + "reconstruction/bun_zipper_res4.ply", loads(453, 948)},
  };
}

std::vector<fs::path> plyFilesUnder(const fs::path& folder) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    if (entry.is_regular_file() && entry.path().extension() == ".ply")
      files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

void checkWellFormed(const rt::TriangleMesh& mesh) {
  for (const glm::uvec3& face : mesh.faces) {
    CHECK(std::max({face.x, face.y, face.z}) < mesh.positions.size());
  }
  for (const glm::vec3& normal : mesh.normals) CHECK(glm::length(normal) == doctest::Approx(1));
  for (const glm::vec2& uv : mesh.uvs) CHECK((std::isfinite(uv.x) && std::isfinite(uv.y)));
}

void checkOutcome(const fs::path& file, const Expected& expected) {
  try {
    const rt::TriangleMesh mesh = rt::loadPly(file);
    CHECK_MESSAGE(expected.error.empty(), "loaded, but expected: " << expected.error);
    CHECK(mesh.positions.size() == expected.vertices);
    CHECK(mesh.faces.size() == expected.triangles);
    CHECK(mesh.normals.size() == (expected.normals ? expected.vertices : 0));
    CHECK(mesh.uvs.size() == (expected.uvs ? expected.vertices : 0));
    checkWellFormed(mesh);
  } catch (const rt::Error& error) {
    const std::string message = error.what();
    CHECK_MESSAGE(!expected.error.empty(), "unexpected error: " << message);
    CHECK(contains(message, file.string() + ": byte "));
    CHECK(contains(message, expected.error));
    CHECK(!contains(message, "\n"));
  }
}

void checkLoadsOrFailsCleanly(const fs::path& file) {
  try {
    checkWellFormed(rt::loadPly(file));
  } catch (const rt::Error& error) {
    CHECK(contains(error.what(), file.string() + ": "));
  }
}

rt::TriangleMesh loadAsset(const fs::path& assets, const std::string& relative) {
  return rt::loadPly(assets / relative);
}

bool near(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b, float tolerance) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (glm::length(a[i] - b[i]) > tolerance) return false;
  }
  return true;
}

// ASCII files print fewer digits than a float holds.
void checkSameMesh(const rt::TriangleMesh& binary, const rt::TriangleMesh& ascii) {
  CHECK(near(binary.positions, ascii.positions, 1e-5f));
  CHECK(binary.faces == ascii.faces);
  CHECK(near(binary.normals, ascii.normals, 1e-5f));
  CHECK(binary.uvs.size() == ascii.uvs.size());
}

}  // namespace

TEST_SUITE("scene ply: shared files" * rt::test::needsShared()) {
  TEST_CASE("every file under assets/ply loads or is rejected as expected") {
    const fs::path assets = plyAssets();
    const std::map<std::string, Expected> expected = expectedOutcomes();
    size_t known = 0;
    for (const fs::path& file : plyFilesUnder(assets)) {
      const std::string relative = file.lexically_relative(assets).generic_string();
      CAPTURE(relative);
      const auto found = expected.find(relative);
      if (found == expected.end()) {
        // A file added later: it must still load or fail with one clean line.
        MESSAGE("no expectation listed for " << relative);
        checkLoadsOrFailsCleanly(file);
        continue;
      }
      ++known;
      checkOutcome(file, found->second);
    }
    CHECK(known == expected.size());
  }

  TEST_CASE("the Stanford bunny: known vertex, bounds, faces") {
    const fs::path assets = plyAssets();
    const rt::TriangleMesh bunny =
        loadAsset(assets, "stanford-bunny/bunny/reconstruction/bun_zipper.ply");
    CHECK(bunny.positions[0] == glm::vec3(-0.0378297f, 0.12794f, 0.00447467f));
    CHECK(bunny.faces[0] == glm::uvec3(21216, 21215, 20399));
    glm::vec3 low(1e9f), high(-1e9f);
    for (const glm::vec3& p : bunny.positions) {
      low = glm::min(low, p);
      high = glm::max(high, p);
    }
    CHECK(low == glm::vec3(-0.0946899f, 0.0329874f, -0.0618736f));
    CHECK(high == glm::vec3(0.0610091f, 0.187321f, 0.0587997f));
    // tinyply's copy spells the types float32/uint8/int32 and was "modified by
    // flipply": the same vertices, every face wound the other way.
    const rt::TriangleMesh flipped =
        loadAsset(assets, "edge-cases/tinyply-assets/assets/bunny.ply");
    CHECK(flipped.positions == bunny.positions);
    REQUIRE(flipped.faces.size() == bunny.faces.size());
    size_t reversed = 0;
    for (size_t i = 0; i < bunny.faces.size(); ++i) {
      const glm::uvec3 face = bunny.faces[i];
      reversed += flipped.faces[i] == glm::uvec3(face.z, face.y, face.x) ||
                  flipped.faces[i] == glm::uvec3(face.x, face.z, face.y) ||
                  flipped.faces[i] == glm::uvec3(face.y, face.x, face.z);
    }
    CHECK(reversed == bunny.faces.size());
  }

  TEST_CASE("a PLY file on its own is a scene: the mesh in grey, framed like an OBJ file") {
    const fs::path file = plyAssets() / "stanford-bunny/bunny/reconstruction/bun_zipper.ply";
    const rt::Scene scene = rt::loadSceneFile(file);
    CHECK(scene.fileKind == "PLY");
    CHECK(scene.conventions == rt::Conventions::Textbook);
    REQUIRE(scene.meshes.size() == 1);
    CHECK(scene.meshes[0].faces.size() == 69451);
    REQUIRE(scene.shapes.size() == 1);
    CHECK(std::get<rt::MeshInstance>(scene.shapes[0].geometry).mesh == 0);
    CHECK(scene.shapes[0].label == "bun_zipper.ply");
    REQUIRE(scene.materials.size() == 1);
    CHECK(scene.materials[0].diffuseColor == glm::vec3(0.8f));
    CHECK(scene.pointLights.size() == 1);
    CHECK(scene.camera.width == 800);
    // The camera looks at the bunny: its centre is straight ahead.
    const glm::dvec3 centre(-0.01684, 0.11013, -0.00154);  // the middle of its bounds
    const glm::vec3 toCentre = glm::normalize(glm::vec3(centre - scene.camera.position));
    CHECK(glm::dot(toCentre, scene.camera.forward) > 0.999f);
    // A point cloud on its own is refused with the reader's one line.
    CHECK_THROWS_WITH_AS(
        rt::loadSceneFile(plyAssets() / "edge-cases/assimp-testmodels-deb/PLY/points.ply"),
        doctest::Contains("points.ply: byte 203: no faces"), rt::Error);
  }

  TEST_CASE("binary little endian, big endian and ASCII versions agree") {
    const fs::path assets = plyAssets();
    const std::string happly = "edge-cases/happly-sampledata/test/sampledata/platonic_shelf";
    const rt::TriangleMesh little = loadAsset(assets, happly + ".ply");
    const rt::TriangleMesh big = loadAsset(assets, happly + "_big_endian.ply");
    CHECK(little.positions == big.positions);  // bit for bit
    CHECK(little.faces == big.faces);
    checkSameMesh(little, loadAsset(assets, happly + "_ascii.ply"));
    const std::string draco = "edge-cases/draco-testdata/testdata/test_pos_color";
    checkSameMesh(loadAsset(assets, draco + ".ply"), loadAsset(assets, draco + "_ascii.ply"));
    const std::string ico = "edge-cases/tinyply-assets/assets/icosahedron";
    checkSameMesh(loadAsset(assets, ico + ".ply"), loadAsset(assets, ico + "_ascii.ply"));
  }

  TEST_CASE("cubes: 8 corners, 12 triangles, quads fanned") {
    const fs::path assets = plyAssets();
    for (const char* name : {"edge-cases/assimp-testmodels-deb/PLY/cube.ply",
                             "edge-cases/assimp-testmodels-deb/PLY/cube_binary.ply",
                             "edge-cases/draco-testdata/testdata/cube_quads.ply"}) {
      CAPTURE(name);
      const rt::TriangleMesh cube = loadAsset(assets, name);
      REQUIRE(cube.positions.size() == 8);
      CHECK(cube.faces.size() == 12);
      // The corners of the unit cube, each once.
      std::set<std::array<float, 3>> corners;
      for (const glm::vec3& p : cube.positions) {
        CHECK(glm::all(glm::equal(p, glm::round(p))));
        CHECK(glm::all(glm::lessThanEqual(glm::abs(p - 0.5f), glm::vec3(0.5f))));
        corners.insert({p.x, p.y, p.z});
      }
      CHECK(corners.size() == 8);
    }
    const rt::TriangleMesh quads =
        loadAsset(assets, "edge-cases/draco-testdata/testdata/cube_quads.ply");
    CHECK(quads.faces[0] == glm::uvec3(0, 1, 2));  // "4 0 1 2 3"
    CHECK(quads.faces[1] == glm::uvec3(0, 2, 3));
  }

  TEST_CASE("CR-only header: the carriage return that starts the data is data") {
    const fs::path assets = plyAssets();
    // The two files differ only in the first data byte (0x99 vs 0x0D), the
    // low byte of vertex 0's x; a reader that ate the CR would misread all.
    const rt::TriangleMesh box = loadAsset(assets, "edge-cases/draco-testdata/testdata/Box.ply");
    const rt::TriangleMesh delim =
        loadAsset(assets, "edge-cases/draco-testdata/testdata/delim_test.ply");
    CHECK(box.positions[0].x != delim.positions[0].x);
    CHECK(std::abs(box.positions[0].x - delim.positions[0].x) < 1e-4f);
    CHECK(std::equal(box.positions.begin() + 1, box.positions.end(), delim.positions.begin() + 1));
    CHECK(box.faces == delim.faces);
  }

  TEST_CASE("Wuson: normals are unit, (s, t) texture coordinates are read") {
    const fs::path assets = plyAssets();
    const rt::TriangleMesh wuson =
        loadAsset(assets, "edge-cases/assimp-testmodels-deb/PLY/Wuson.ply");
    CHECK(wuson.uvs[0] == glm::vec2(0.681180f, 0.275678f));
    CHECK(glm::length(wuson.normals[0] - glm::vec3(0.241919f, -0.961129f, 0.133063f)) < 1e-5f);
    CHECK(wuson.faces.back() == glm::uvec3(11181, 11182, 11183));
  }
}

TEST_SUITE("scene ply: synthetic files") {
  TEST_CASE("every scalar type name, in ASCII and both binary byte orders") {
    const std::vector<std::string> types = {
        "char", "uchar", "short", "ushort", "int",   "uint",   "float",   "double",
        "int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"};
    const std::vector<std::string> integers = {"char",  "uchar",  "short", "ushort",
                                               "int",   "uint",   "int8",  "uint8",
                                               "int16", "uint16", "int32", "uint32"};
    for (const std::string& type : types) {
      for (size_t i = 0; i < integers.size(); ++i) {
        const std::string& count = integers[i];
        const std::string& index = integers[(i + 5) % integers.size()];
        TestElement vertices = vertexElement(kSquare, type);
        // An extra property of every type, to be skipped.
        for (const std::string& extra : types) {
          vertices.properties.push_back({extra, "extra_" + extra, ""});
          for (auto& record : vertices.records) record.push_back(100);
        }
        const std::vector<TestElement> mesh = {vertices, faceElement({{0, 1, 2, 3}}, count, index)};
        for (Layout layout : {Layout::Ascii, Layout::LittleEndian, Layout::BigEndian}) {
          INFO(type, " ", count, " ", index, " ", formatName(layout));
          const rt::TriangleMesh loaded = rt::parsePly(writePly(mesh, layout), "t.ply");
          CHECK(loaded.positions == kSquare);
          CHECK(loaded.faces == std::vector<glm::uvec3>{{0, 1, 2}, {0, 2, 3}});
        }
      }
    }
  }

  TEST_CASE("normals, UV name pairs, skipped lists and polygons in every layout") {
    for (Layout layout : {Layout::Ascii, Layout::LittleEndian, Layout::BigEndian}) {
      CAPTURE(std::string(formatName(layout)));
      const rt::TriangleMesh mesh = rt::parsePly(writePly(richMesh(), layout), "t.ply");
      CHECK(mesh.positions == kSquare);
      CHECK(mesh.normals == std::vector<glm::vec3>(4, glm::vec3(0, 0, 1)));
      REQUIRE(mesh.uvs.size() == 4);
      CHECK(mesh.uvs[2] == glm::vec2(1, 1));
      CHECK(mesh.faces == std::vector<glm::uvec3>{{0, 1, 2}, {0, 2, 3}, {0, 2, 3}});
    }
    for (const auto& [u, v] : std::vector<std::pair<std::string, std::string>>{
             {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}}) {
      std::vector<TestElement> mesh = richMesh();
      mesh[0].properties[7].name = u;
      mesh[0].properties[8].name = v;
      CHECK(rt::parsePly(writePly(mesh, Layout::Ascii), "t.ply").uvs.size() == 4);
    }
    std::vector<TestElement> partial = richMesh();
    partial[0].properties[8].name = "w";  // u without v: no UVs
    CHECK(rt::parsePly(writePly(partial, Layout::Ascii), "t.ply").uvs.empty());
  }

  TEST_CASE("vertex colours: integers over their range, floats in [0, 1], decoded from sRGB") {
    auto coloured = [](const std::string& type, const std::array<std::string, 3>& names,
                       const std::vector<glm::dvec3>& colors) {
      TestElement vertices{"vertex",
                           {{"float", "x", ""},
                            {"float", "y", ""},
                            {"float", "z", ""},
                            {type, names[0], ""},
                            {type, names[1], ""},
                            {type, names[2], ""}},
                           {}};
      for (size_t i = 0; i < kSquare.size(); ++i) {
        const glm::vec3& p = kSquare[i];
        vertices.records.push_back({p.x, p.y, p.z, colors[i].x, colors[i].y, colors[i].z});
      }
      TestElement faces{"face", {{"int", "vertex_indices", "uchar"}}, {{4, 0, 1, 2, 3}}};
      return std::vector<TestElement>{vertices, faces};
    };
    const std::array<std::string, 3> rgb = {"red", "green", "blue"};
    constexpr float kHalfGrey = 0.21586f;  // sRGB 128 decoded
    for (Layout layout : {Layout::Ascii, Layout::LittleEndian, Layout::BigEndian}) {
      CAPTURE(std::string(formatName(layout)));
      const rt::TriangleMesh bytes = rt::parsePly(
          writePly(coloured("uchar", rgb, {{255, 0, 128}, {0, 255, 0}, {255, 255, 255}, {0, 0, 0}}),
                   layout),
          "t.ply");
      REQUIRE(bytes.colors.size() == 4);
      CHECK(bytes.colors[0].x == 1.0f);
      CHECK(bytes.colors[0].y == 0.0f);
      CHECK(bytes.colors[0].z == doctest::Approx(kHalfGrey).epsilon(1e-4));
      CHECK(bytes.colors[2] == glm::vec3(1.0f));
      CHECK(bytes.colors[3] == glm::vec3(0.0f));
    }
    const rt::TriangleMesh shorts = rt::parsePly(
        writePly(coloured("ushort", rgb, {{65535, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}}),
                 Layout::LittleEndian),
        "t.ply");
    CHECK(shorts.colors[0] == glm::vec3(1, 0, 0));
    // Floats, MeshLab's names: out of range is clamped.
    const rt::TriangleMesh floats =
        rt::parsePly(writePly(coloured("float", {"diffuse_red", "diffuse_green", "diffuse_blue"},
                                       {{2, -1, 0.5}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}}),
                              Layout::Ascii),
                     "t.ply");
    REQUIRE(floats.colors.size() == 4);
    CHECK(floats.colors[0].x == 1.0f);
    CHECK(floats.colors[0].y == 0.0f);
    CHECK(floats.colors[0].z == doctest::Approx(0.21404).epsilon(1e-4));
    const rt::TriangleMesh shortNames = rt::parsePly(
        writePly(coloured("uchar", {"r", "g", "b"}, std::vector<glm::dvec3>(4, {0, 0, 255})),
                 Layout::Ascii),
        "t.ply");
    CHECK(shortNames.colors == std::vector<glm::vec3>(4, glm::vec3(0, 0, 1)));
    // All white changes nothing: no colours, so the kernels are built without them.
    const rt::TriangleMesh white =
        rt::parsePly(writePly(coloured("uchar", rgb, std::vector<glm::dvec3>(4, glm::dvec3(255))),
                              Layout::Ascii),
                     "t.ply");
    CHECK(white.colors.empty());
    // richMesh has "red" alone: no colours.
    CHECK(rt::parsePly(writePly(richMesh(), Layout::Ascii), "t.ply").colors.empty());
  }

  TEST_CASE("normals are normalised; zero normals come from the faces around them") {
    std::vector<TestElement> mesh = richMesh();
    mesh[0].records[0][6] = 2;  // nz = 2
    mesh[0].records[1][6] = 0;  // (0, 0, 0)
    const rt::TriangleMesh loaded = rt::parsePly(writePly(mesh, Layout::Ascii), "t.ply");
    CHECK(loaded.normals[0] == glm::vec3(0, 0, 1));
    CHECK(glm::length(loaded.normals[1] - glm::vec3(0, 0, 1)) < 1e-6f);
  }

  TEST_CASE("per-face texcoord lists: vertices split only along seams, in every layout") {
    // Two triangles and a quad over five vertices; vertex 2 has other
    // coordinates in the quad than in the triangles (a seam), the others one
    // pair each. Each vertex has its own normal, which its copies keep.
    const std::vector<glm::vec3> positions = {
        {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 1}};
    TestElement vertices{"vertex",
                         {{"float", "x", ""},
                          {"float", "y", ""},
                          {"float", "z", ""},
                          {"float", "nx", ""},
                          {"float", "ny", ""},
                          {"float", "nz", ""}},
                         {}};
    for (size_t v = 0; v < positions.size(); ++v) {
      const glm::vec3 p = positions[v];
      vertices.records.push_back({p.x, p.y, p.z, 0, 0.6 * double(v % 2), v % 2 ? 0.8 : 1.0});
    }
    TestElement faces{
        "face", {{"int", "vertex_indices", "uchar"}, {"float", "texcoord", "uchar"}}, {}};
    faces.records.push_back({3, 0, 1, 2, 6, 0, 0, 1, 0, 1, 1});
    faces.records.push_back({3, 0, 2, 3, 6, 0, 0, 1, 1, 0, 1});
    faces.records.push_back({4, 0, 1, 4, 2, 8, 0, 0, 1, 0, 0.5, 0.5, 0.25, 0.75});
    // The faces come first, as some writers put them.
    const std::vector<TestElement> mesh = {faces, vertices};
    const std::vector<std::vector<glm::vec2>> written = {{{0, 0}, {1, 0}, {1, 1}},
                                                         {{0, 0}, {1, 1}, {0, 1}},
                                                         {{0, 0}, {1, 0}, {0.5, 0.5}},
                                                         {{0, 0}, {0.5, 0.5}, {0.25, 0.75}}};
    const std::vector<std::vector<uint32_t>> corners = {{0, 1, 2}, {0, 2, 3}, {0, 1, 4}, {0, 4, 2}};
    for (Layout layout : {Layout::Ascii, Layout::LittleEndian, Layout::BigEndian}) {
      CAPTURE(std::string(formatName(layout)));
      const rt::TriangleMesh loaded = rt::parsePly(writePly(mesh, layout), "t.ply");
      REQUIRE(loaded.faces.size() == 4);
      REQUIRE(loaded.uvs.size() == loaded.positions.size());
      CHECK(loaded.positions.size() == 6);  // five, and vertex 2's second copy
      CHECK(loaded.normals.size() == loaded.positions.size());
      for (size_t f = 0; f < 4; ++f) {
        for (int c = 0; c < 3; ++c) {
          const uint32_t v = loaded.faces[f][c];
          CHECK(loaded.positions[v] == positions[corners[f][size_t(c)]]);
          CHECK(loaded.uvs[v] == written[f][size_t(c)]);
        }
      }
      // The copies of a split vertex keep the smooth normal of the whole surface.
      for (size_t a = 0; a < loaded.positions.size(); ++a) {
        for (size_t b = 0; b < loaded.positions.size(); ++b) {
          if (loaded.positions[a] == loaded.positions[b])
            CHECK(loaded.normals[a] == loaded.normals[b]);
        }
      }
    }
    // An empty list is a face without coordinates (zeros); a list of the wrong
    // length is an error that names the face.
    TestElement untextured = faces;
    untextured.records[1] = {3, 0, 2, 3, 0};
    const rt::TriangleMesh loaded =
        rt::parsePly(writePly({vertexElement(positions), untextured}, Layout::Ascii), "t.ply");
    CHECK(loaded.uvs[loaded.faces[1].z] == glm::vec2(0.0f));
    TestElement short_ = faces;
    short_.records[1] = {3, 0, 2, 3, 4, 0, 0, 1, 1};
    CHECK(contains(plyError(writePly({vertexElement(positions), short_}, Layout::Ascii)),
                   "face 1: the face has 3 corners but texture coordinates for 2"));
    TestElement odd = faces;
    odd.records[0] = {3, 0, 1, 2, 5, 0, 0, 1, 0, 1};
    CHECK(contains(plyError(writePly({vertexElement(positions), odd}, Layout::Ascii)),
                   "face 0: 'texcoord' has 5 values, not a u and a v for each corner"));
  }

  TEST_CASE("faces before vertices, extra elements in between, index lists named vertex_index") {
    TestElement faces = faceElement({{2, 1, 0}}, "int", "uint");
    faces.properties[0].name = "vertex_index";
    faces.properties.insert(faces.properties.begin(), {"uchar", "flags", ""});
    faces.records[0].insert(faces.records[0].begin(), 9);
    const TestElement material{"material",
                               {{"double", "shine", ""}, {"short", "names", "uint"}},
                               {{0.5, 2, 7, 8}, {0.25, 0}}};
    const std::vector<TestElement> mesh = {faces, material, vertexElement(kSquare, "double")};
    for (Layout layout : {Layout::Ascii, Layout::LittleEndian, Layout::BigEndian}) {
      CAPTURE(std::string(formatName(layout)));
      const rt::TriangleMesh loaded = rt::parsePly(writePly(mesh, layout), "t.ply");
      CHECK(loaded.positions == kSquare);
      CHECK(loaded.faces == std::vector<glm::uvec3>{{2, 1, 0}});
    }
  }

  TEST_CASE("tristrips: alternating winding, -1 restarts, stitching triangles dropped") {
    const TestElement strips{
        "tristrips", {{"int", "vertex_indices", "int"}}, {{9, 0, 1, 2, 3, -1, 0, 2, 2, 3}}};
    const std::vector<TestElement> mesh = {vertexElement(kSquare), strips};
    for (Layout layout : {Layout::Ascii, Layout::LittleEndian, Layout::BigEndian}) {
      const rt::TriangleMesh loaded = rt::parsePly(writePly(mesh, layout), "t.ply");
      CHECK(loaded.faces == std::vector<glm::uvec3>{{0, 1, 2}, {2, 1, 3}});
    }
    const TestElement degenerate{"tristrips", {{"int", "vertex_indices", "int"}}, {{3, 0, 0, 1}}};
    CHECK(contains(plyError(writePly({vertexElement(kSquare), degenerate}, Layout::Ascii)),
                   "no faces: every tristrip is degenerate"));
  }

  TEST_CASE("LF, CRLF and CR-only line endings; the ending after end_header is one line ending") {
    // Vertex 0's x starts (little endian) with the byte 0x0A or 0x0D.
    const std::vector<glm::vec3> square = {{std::bit_cast<float>(0x3F80000Au), 0, 0},
                                           {std::bit_cast<float>(0x3F80000Du), 0, 0},
                                           {1, 1, 0}};
    const std::vector<TestElement> mesh = {vertexElement(square), faceElement({{0, 1, 2}})};
    for (const std::string eol : {"\n", "\r\n", "\r"}) {
      for (Layout layout : {Layout::Ascii, Layout::LittleEndian, Layout::BigEndian}) {
        const std::string text = writePly(mesh, layout, eol);
        CHECK(rt::parsePly(text, "t.ply").positions == square);
      }
    }
    std::string crlfAscii = writePly(mesh, Layout::Ascii, "\r\n");
    std::string body = bodyOf(mesh, Layout::Ascii);
    crlfAscii.replace(crlfAscii.size() - body.size(), body.size(), "\r\n\r\n");
    for (const glm::vec3& p : square) crlfAscii += std::to_string(p.x) + " 0 0\r\n";
    crlfAscii += "3 0 1 2\r\n\r\n";
    CHECK(rt::parsePly(crlfAscii, "t.ply").faces.size() == 1);  // blank lines between records
  }

  TEST_CASE("comments, obj_info, a banner before the first element, blanks in the header") {
    const std::string text =
        "ply\n"
        "format   ascii 1.0\t\n"
        "Created by some exporter without the word comment\n"
        "comment one\n"
        "obj_info num_cols 512\n"
        "\n"
        " element vertex\t3\n"
        "property float x\nproperty   float y\nproperty float z\n"
        "\telement face 1\n"
        "property list uchar int vertex_indices   \n"
        "comment after the properties\n"
        "end_header\n"
        "+0 0 0\n1 0 0\n000 1.0e0 0\n"
        "3 0 1 2\n";
    CHECK(rt::parsePly(text, "t.ply").faces.size() == 1);
  }
}

TEST_SUITE("scene ply: rejected input") {
  TEST_CASE("header errors name the byte where the bad line starts") {
    CHECK(plyError("") == "t.ply: byte 0: empty file");
    CHECK(plyError("PLY\n") == "t.ply: byte 0: not a PLY file (the first line must be 'ply')");
    CHECK(plyError("ply\nformat ascii 1.0\nelement vertex 0\n") ==
          "t.ply: byte 38: the header has no 'end_header' line");
    CHECK(plyError("ply\nformat ebcdic 1.0\nend_header\n") ==
          "t.ply: byte 4: unknown format 'ebcdic' (expected ascii, binary_little_endian or "
          "binary_big_endian)");
    CHECK(plyError("ply\nformat ascii 2.0\n") == "t.ply: byte 4: unsupported PLY version '2.0'");
    CHECK(plyError("ply\nelement vertex 1\nend_header\n") ==
          "t.ply: byte 21: the header has no 'format' line");
    const std::string start = "ply\nformat ascii 1.0\n";
    CHECK(
        contains(plyError(start + "property float x\n"), "byte 21: a property before any element"));
    CHECK(contains(plyError(start + "element vertex 1\nproperty half x\n"),
                   "byte 38: unknown property type 'half' (expected char, uchar"));
    CHECK(contains(plyError(start + "element vertex -1\n"),
                   "element 'vertex': the count must be a non-negative integer, got '-1'"));
    CHECK(contains(plyError(start + "element vertex 18446744073709551616\n"),
                   "the count must be a non-negative integer"));
    CHECK(contains(plyError(start + "element vertex 1\nelement vertex 1\n"),
                   "byte 38: element 'vertex' is declared twice"));
    CHECK(contains(plyError(start + "element vertex 1\nproperty float x\nproperty float x\n"),
                   "property 'x' of element 'vertex' is declared twice"));
    CHECK(contains(plyError(start + "element face 1\nproperty list float int vertex_indices\n"),
                   "a list length type must be an integer type, not float"));
    CHECK(contains(plyError(start + "element vertex 1\nproperty float x\nbogus line\n"),
                   "byte 55: unknown header line 'bogus line'"));
  }

  TEST_CASE("the header must describe a mesh") {
    const std::string start = "ply\nformat ascii 1.0\n";
    const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
    const std::string faces = "element face 1\nproperty list uchar int vertex_indices\n";
    CHECK(plyError(start + "element vertex 3\n" + xyz + "end_header\n") ==
          "t.ply: byte 89: " + kNoFaces + " (a point cloud or range scan is not a mesh)");
    CHECK(contains(plyError(start + "element vertex 3\n" + xyz +
                            "element face 0\nproperty list uchar int vertex_indices\nend_header\n"),
                   kNoFaces));
    CHECK(contains(plyError(start + faces + "end_header\n3 0 1 2\n"),
                   "the header declares no 'vertex' element"));
    CHECK(contains(plyError(start + "element vertex 3\nproperty float x\nproperty float y\n" +
                            faces + "end_header\n"),
                   "byte 21: element 'vertex' needs a scalar property 'z'"));
    CHECK(contains(plyError(start + "element vertex 3\n" + xyz +
                            "element face 1\nproperty list uchar float vertex_indices\n"
                            "end_header\n"),
                   "property 'vertex_indices' of element 'face' must be a list of integers"));
    CHECK(contains(plyError(start + "element vertex 3\n" + xyz +
                            "element face 1\nproperty list uchar int corners\nend_header\n"),
                   "element 'face' has no 'vertex_indices' or 'vertex_index' list"));
    CHECK(contains(plyError(start + "element vertex 4294967296\n" + xyz + faces + "end_header\n"),
                   "byte 21: too many vertices (4294967296; at most 4294967294)"));
  }

  TEST_CASE("counts the file cannot hold fail at once, without allocating") {
    const std::string header =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\nelement face 1000000000000\n"
        "property list uchar int vertex_indices\nend_header\n";
    const std::string error = plyError(header + std::string(36 + 13 * 4, '\0'));
    CHECK(error == prefixAt(header, "element face") +
                       "element 'face' declares 1000000000000 records, more than the 88 bytes of "
                       "data can hold");
    std::string ascii = header;
    ascii.replace(ascii.find("binary_little_endian"), 20, "ascii");
    CHECK(contains(plyError(ascii + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
                   "declares 1000000000000 records"));
    std::string maxed = header;
    maxed.replace(maxed.find("1000000000000"), 13, "18446744073709551615");
    CHECK(
        contains(plyError(maxed + std::string(88, '\0')), "declares 18446744073709551615 records"));
    // Elements without properties take no bytes, however many they claim.
    std::string empty = writePly({vertexElement(kSquare), faceElement({{0, 1, 2}})}, Layout::Ascii);
    empty.insert(empty.find("end_header"), "element nothing 1000000000000\n");
    CHECK(rt::parsePly(empty, "t.ply").faces.size() == 1);
  }

  TEST_CASE("bad list lengths") {
    const auto faceWith = [](const std::vector<double>& record, const std::string& countType,
                             Layout layout) {
      // The second face is long enough that the bad first one still passes
      // the up-front size check and is read.
      TestElement faces{
          "face", {{"int", "vertex_indices", countType}}, {record, {8, 0, 1, 2, 3, 0, 1, 2, 3}}};
      return writePly({vertexElement(kSquare), faces}, layout);
    };
    for (Layout layout : {Layout::Ascii, Layout::LittleEndian, Layout::BigEndian}) {
      CAPTURE(std::string(formatName(layout)));
      CHECK(contains(plyError(faceWith({2, 0, 1}, "uchar", layout)),
                     "face 0: a face needs at least 3 vertex indices, got 2"));
      CHECK(contains(plyError(faceWith({-1}, "int", layout)), "face 0: negative list length -1"));
      CHECK(contains(plyError(faceWith({4e9, 0, 1, 2}, "uint", layout)),
                     "face 0: list length 4000000000 of 'vertex_indices' does not fit in the"));
    }
  }

  TEST_CASE("bad indices and values name the exact byte") {
    std::string text = writePly({vertexElement(kSquare), faceElement({{0, 1, 9}})}, Layout::Ascii);
    CHECK(plyError(text) == prefixAt(text, "9\n") +
                                "face 0: vertex index 9 is out of range (the file has 4 vertices)");
    text = writePly({vertexElement(kSquare), faceElement({{0, -1, 2}})}, Layout::LittleEndian);
    const size_t index = text.size() - 8;  // the second of three 4-byte indices
    CHECK(plyError(text) == "t.ply: byte " + std::to_string(index) +
                                ": face 0: vertex index -1 is out of range (the file has 4 "
                                "vertices)");
    const std::vector<TestElement> good = {vertexElement(kSquare), faceElement({{0, 1, 2}})};
    text = writePly(good, Layout::Ascii);
    const size_t body = text.find("end_header\n") + 11;
    const auto broken = [&](const std::string& from, const std::string& to) {
      std::string copy = text;
      copy.replace(copy.find(from, body), from.size(), to);
      return plyError(copy);
    };
    CHECK(contains(broken("3 0 1 2", "3 0 1.5 2"),
                   "face 0: expected an integer (int) for 'vertex_indices', got '1.5'"));
    CHECK(contains(broken("3 0 1 2", "300 0 1 2"), "face 0: 300 is out of range for uchar"));
    CHECK(contains(broken("1 1 0", "1 abc 0"), "vertex 2: 'abc' is not a number"));
    CHECK(contains(broken("1 1 0", "1 nan 0"), "vertex 2: 'y' is not a finite float"));
    CHECK(contains(broken("1 1 0", "1 -inf 0"), "vertex 2: 'y' is not a finite float"));
    CHECK(contains(broken("1 1 0", "1 1e39 0"), "vertex 2: 'y' is not a finite float"));
    CHECK(contains(broken("1 1 0", "1 1 0 5"), "the line of vertex 2 has more values than"));
    CHECK(
        contains(broken("1 1 0", "1.000 1.000"), "the line of vertex 2 ends before property 'z'"));
    CHECK(contains(broken("3 0 1 2\n", "3 0 1 2\n3 0 1 2\n"),
                   "unexpected data after face 0, the last record the header declares"));
    std::vector<TestElement> nanMesh = good;
    nanMesh[0].records[1][0] = std::nan("");
    CHECK(contains(plyError(writePly(nanMesh, Layout::BigEndian)),
                   "vertex 1: 'x' is not a finite float"));
    CHECK(contains(plyError(writePly(good, Layout::LittleEndian) + "xyz"),
                   "3 bytes of unexpected data after face 0"));
  }

  TEST_CASE("a binary file cut at any byte fails cleanly; ASCII cuts load or fail cleanly") {
    for (Layout layout : {Layout::LittleEndian, Layout::BigEndian, Layout::Ascii}) {
      const std::string text = writePly(richMesh(), layout);
      size_t loaded = 0;
      for (size_t length = 0; length < text.size(); ++length) {
        try {
          rt::parsePly(std::string_view(text).substr(0, length), "t.ply");
          ++loaded;
        } catch (const rt::Error& error) {
          CHECK(contains(error.what(), "t.ply: byte "));
        }
      }
      // Only cuts in the final line's last number or newline can still parse.
      CHECK(loaded <= (layout == Layout::Ascii ? 2u : 0u));
    }
    // Most cuts fail the up-front size check; this one gets past it.
    const std::string text = writePly(richMesh(), Layout::LittleEndian);
    CHECK(plyError(text.substr(0, text.size() - 1)) ==
          "t.ply: byte " + std::to_string(text.size() - 4) +
              ": the file ends inside face 1 at property 'weights' (the header declares 2 "
              "'face' records)");
    CHECK(contains(plyError(text.substr(0, text.size() - 20)),
                   "more than the " +
                       std::to_string(text.size() - 20 - text.find("end_header\n") - 11) +
                       " bytes of data can hold"));
  }

  TEST_CASE("any byte replaced: loads or fails with rt::Error, never anything else") {
    for (Layout layout : {Layout::LittleEndian, Layout::Ascii}) {
      const std::string text = writePly(richMesh(), layout);
      for (size_t at = 0; at < text.size(); ++at) {
        for (char value : {'\0', '\xff', '\x7f', '\x80', '\n', '\r', ' ', '-', '9'}) {
          std::string copy = text;
          copy[at] = value;
          try {
            rt::parsePly(copy, "t.ply");
          } catch (const rt::Error&) {
          } catch (const std::exception& error) {
            FAIL("not an rt::Error at byte " << at << ": " << error.what());
          }
        }
      }
    }
  }
}

TEST_SUITE("scene ply: files") {
  TEST_CASE("loadPly reads files and names them in errors") {
    const std::string text = writePly(richMesh(), Layout::BigEndian);
    const fs::path file = writeFile("rich_big_endian.ply", text);
    CHECK(rt::loadPly(file).faces.size() == 3);
    const fs::path broken = writeFile("broken.ply", text.substr(0, text.size() - 1));
    try {
      rt::loadPly(broken);
      FAIL("a truncated file must fail");
    } catch (const rt::Error& error) {
      CHECK(contains(error.what(), broken.string() + ": byte " + std::to_string(text.size() - 4) +
                                       ": the file ends inside face 1"));
    }
    const fs::path missing = outputDir() / "missing.ply";
    try {
      rt::loadPly(missing);
      FAIL("a missing file must fail");
    } catch (const rt::Error& error) {
      CHECK(std::string(error.what()) ==
            missing.string() + ": cannot open: No such file or directory");
    }
    CHECK_THROWS_AS(rt::loadPly(outputDir()), rt::Error);
  }

  TEST_CASE("a PLY on its own draws its TextureFile, its coordinates up the image") {
    // A 2 x 2 texture: red and green on the top row, blue and white below.
    fs::create_directories(outputDir() / "tex dir");
    rt::ImageF texture{2, 2, {1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1, 1, 1, 1, 1}};
    rt::writeImage(outputDir() / "tex dir" / "corners.png", texture, {});
    // A unit square facing +z, red vertex colours, MeshLab's corner lists.
    auto textured = [](const std::string& comment, bool texcoords) {
      std::string ply = "ply\nformat ascii 1.0\n" + comment +
                        "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                        "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                        "element face 2\nproperty list uchar int vertex_indices\n";
      if (texcoords) ply += "property list uchar float texcoord\n";
      ply += "end_header\n0 0 0 255 0 0\n1 0 0 255 0 0\n1 1 0 255 0 0\n0 1 0 255 0 0\n";
      ply += texcoords ? "3 0 1 2 6 0 0 1 0 1 1\n3 0 2 3 6 0 0 1 1 0 1\n" : "3 0 1 2\n3 0 2 3\n";
      return ply;
    };
    const fs::path file =
        writeFile("textured.ply", textured("comment TextureFile tex dir\\corners.png\n", true));
    rt::Scene scene = rt::loadSceneFile(file);
    REQUIRE(scene.textures.size() == 1);
    CHECK(scene.materials[0].diffuseTexture == 0);
    CHECK(scene.materials[0].texture == outputDir() / "tex dir" / "corners.png");
    const rt::TriangleMesh& mesh = scene.meshes[0];
    CHECK(mesh.colors.empty());
    auto warned = [&](const std::string& what) {
      return std::any_of(scene.warnings.begin(), scene.warnings.end(),
                         [&](const std::string& line) { return contains(line, what); });
    };
    CHECK(warned("the vertex colours are ignored, the texture is drawn"));
    for (size_t v = 0; v < mesh.positions.size(); ++v) {  // (u, v) of a corner is (x, y) here
      CHECK(mesh.uvs[v] == glm::vec2(mesh.positions[v].x, 1.0f - mesh.positions[v].y));
    }
    // Rendered: red at the top left, green top right, blue bottom left.
    rt::Renderer renderer(rt::test::gpu(), rt::test::shaderCompiler());
    rt::RenderOptions options;
    options.width = 48;
    options.height = 48;
    options.samplesPerPixel = 1;
    const rt::ImageF image = renderer.render(scene, options);
    rt::test::checkNoValidationMessages();
    // Where a channel dominates: how many pixels, and their mean column and row.
    auto dominant = [&](int channel) {
      glm::dvec3 found(0.0);
      for (size_t i = 0; i < image.rgba.size(); i += 4) {
        const float c = image.rgba[i + size_t(channel)];
        const float others = image.rgba[i] + image.rgba[i + 1] + image.rgba[i + 2] - c;
        if (c > 0.2f && c > 2.0f * others) {
          found += glm::dvec3(1.0, double(i / 4 % image.width), double(i / 4 / image.width));
        }
      }
      return glm::dvec3(found.x, found.y / found.x, found.z / found.x);
    };
    rt::test::savePng(rt::toneMap(image, {}), "ply-texture-file.png");
    const glm::dvec3 red = dominant(0), green = dominant(1), blue = dominant(2);
    CHECK(red.x > 20);
    CHECK(green.x > 20);
    CHECK(blue.x > 20);
    CHECK(red.y < green.y);  // left of it
    CHECK(red.z < blue.z);   // above it

    // A missing file: the missing-texture squares; no coordinates: no texture.
    scene = rt::loadSceneFile(
        writeFile("missing-texture.ply", textured("comment TextureFile no.png\n", true)));
    CHECK(scene.materials[0].diffuseTexture >= 0);
    CHECK(warned("TextureFile no.png: file not found; drawn with the missing-texture squares"));
    scene = rt::loadSceneFile(
        writeFile("no-uvs.ply", textured("comment TextureFile tex dir/corners.png\n", false)));
    CHECK(scene.materials[0].diffuseTexture == -1);
    CHECK(scene.meshes[0].colors.size() == 4);
    CHECK(warned("ignored, the mesh has no texture coordinates"));
    // A file that is no image: one line naming the PLY and the texture.
    writeFile("not-an-image.png", "not an image");
    const fs::path broken =
        writeFile("broken-texture.ply", textured("comment TextureFile not-an-image.png\n", true));
    try {
      rt::loadSceneFile(broken);
      FAIL("a texture that is no image must fail");
    } catch (const rt::Error& error) {
      CHECK(contains(error.what(),
                     broken.string() + ": TextureFile not-an-image.png: cannot use texture: "));
    }
  }
}
