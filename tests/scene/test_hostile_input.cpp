// Hostile text in loader messages: keys, type names, header lines and parser
// excerpts come from the file, so they may carry line breaks, terminal escape
// sequences or bytes that are not UTF-8. Every error and warning must still
// be one printable line; syntax errors in glTF JSON give a byte offset.
// Vectors may be tiny (denormal) or huge and must still normalise to unit
// length (a fuzzer finding: denormal PLY normals came out 9% too long).
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
#include <string>

#include "formats/common/MessageText.hpp"
#include "formats/common/UnitVector.hpp"
#include "formats/gltf/GltfLoader.hpp"
#include "formats/json/JsonSceneLoader.hpp"
#include "formats/ply/PlyLoader.hpp"
#include "util/Error.hpp"

namespace fs = std::filesystem;

namespace {

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Printable: no byte below 0x20, no DEL, and no C1 control (U+0080..U+009F).
bool isPrintableLine(const std::string& text) {
  for (size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7F) return false;
    if (c == 0xC2 && i + 1 < text.size() && static_cast<unsigned char>(text[i + 1]) < 0xA0) {
      return false;
    }
  }
  return true;
}

template <typename Load>
std::string errorOf(Load load) {
  try {
    load();
  } catch (const rt::Error& error) {
    return error.what();
  }
  return "";
}

fs::path writeScratch(const std::string& name, const std::string& bytes) {
  const fs::path dir = fs::path(RT_TEST_OUTPUT_DIR) / "hostile";
  fs::create_directories(dir);
  std::ofstream(dir / name, std::ios::binary) << bytes;
  return dir / name;
}

// A scene that loads, with `shape` as its only shape.
std::string sceneWithShape(const std::string& shape) {
  return R"({"camera":{"type":"pinhole","width":8,"height":8,"fov":45,"position":[0,0,0],
    "lookat":[0,0,-1],"up":[0,1,0]},"scene":{"shapes":[)" +
         shape + "]}}";
}

const std::string kSphere = R"({"type":"sphere","center":[0,0,-3],"radius":1,
    "material":{"ks":0.2,"kd":0.8,"specularexponent":10,"diffusecolor":[0.8,0.2,0.2]}})";

}  // namespace

TEST_SUITE("scene hostile messages") {
  TEST_CASE("printableLine escapes controls and broken UTF-8, keeps UTF-8, is idempotent") {
    CHECK(rt::printableLine("plain text: 1.5") == "plain text: 1.5");
    CHECK(rt::printableLine("a\nb\rc\td") == "a\\nb\\rc\\td");
    CHECK(rt::printableLine(std::string("nul\0x", 5)) == "nul\\x00x");
    CHECK(rt::printableLine("esc\x1b[2Jdel\x7f") == "esc\\x1B[2Jdel\\x7F");
    CHECK(rt::printableLine("caf\xc3\xa9 \xe6\x97\xa5 \xf0\x9f\x98\x80") ==
          "caf\xc3\xa9 \xe6\x97\xa5 \xf0\x9f\x98\x80");
    CHECK(rt::printableLine("csi\xc2\x9b") == "csi\\xC2\\x9B");  // C1 control U+009B
    CHECK(rt::printableLine("bad\xff") == "bad\\xFF");
    CHECK(rt::printableLine("overlong\xc0\xaf") == "overlong\\xC0\\xAF");
    CHECK(rt::printableLine("surrogate\xed\xa0\x80") == "surrogate\\xED\\xA0\\x80");
    CHECK(rt::printableLine("cut\xe6\x97") == "cut\\xE6\\x97");
    const std::string once = rt::printableLine("x\n\xff\x1b\xc2\x85y");
    CHECK(rt::printableLine(once) == once);
  }

  TEST_CASE("printableLine cuts long text, never inside an escape") {
    const std::string cut = rt::printableLine(std::string(5000, 'a'));
    CHECK(cut.size() == rt::kMaxMessageLength);
    CHECK(cut.substr(cut.size() - 4) == "a...");
    CHECK(rt::printableLine(cut) == cut);
    const std::string escapes = rt::printableLine(std::string(5000, '\x01'));
    CHECK(escapes.size() <= rt::kMaxMessageLength);
    CHECK(escapes.substr(escapes.size() - 7) == "\\x01...");
    const std::string exact(rt::kMaxMessageLength, 'b');
    CHECK(rt::printableLine(exact) == exact);
  }

  TEST_CASE("JSON scenes: file text in errors and warnings stays on one line") {
    const std::string badType =
        sceneWithShape(R"({"type":"sp\nhe\u001bre","center":[0,0,-3],"radius":1})");
    const std::string error = errorOf([&] { rt::parseJsonScene(badType, "type.json"); });
    CHECK(isPrintableLine(error));
    CHECK(contains(error, "type.json: scene.shapes[0].type: unknown shape type 'sp\\nhe\\x1Bre'"));

    std::string withKey = kSphere;
    withKey.insert(1, R"("co\r\nlor\u009b":1,)");
    const rt::Scene scene = rt::parseJsonScene(sceneWithShape(withKey), "key.json");
    REQUIRE(scene.warnings.size() == 1);
    CHECK(isPrintableLine(scene.warnings[0]));
    CHECK(contains(scene.warnings[0], "unknown key 'co\\r\\nlor\\xC2\\x9B'"));
  }

  TEST_CASE("JSON scenes: invalid UTF-8 in the parser's excerpt is escaped") {
    const std::string text = sceneWithShape(kSphere);
    std::string broken = text;
    broken.replace(broken.find("pinhole"), 7, "pin\xffhole");
    const std::string error = errorOf([&] { rt::parseJsonScene(broken, "utf8.json"); });
    CHECK(isPrintableLine(error));
    CHECK(contains(error, "utf8.json: byte "));
    CHECK(contains(error, "\\xFF"));
  }

  TEST_CASE("PLY: a header line with control characters is quoted printably") {
    const std::string ply =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nbo\x1bgus\x7f\nend_header\n";
    const std::string error = errorOf([&] { rt::parsePly(ply, "ctrl.ply"); });
    CHECK(isPrintableLine(error));
    CHECK(contains(error, "ctrl.ply: byte 55: unknown header line 'bo\\x1Bgus\\x7F'"));
  }

  TEST_CASE("glTF: syntax errors give a byte offset; empty files say so; names stay printable") {
    const fs::path syntax = writeScratch("syntax.gltf", R"({"asset":{"version":"2.0"},,})");
    const std::string error = errorOf([&] { rt::loadGltfScene(syntax); });
    CHECK(contains(error, syntax.string() + ": byte 28: "));
    CHECK(!contains(error, "json.exception"));

    const fs::path empty = writeScratch("empty.gltf", "");
    CHECK(errorOf([&] { rt::loadGltfScene(empty); }) == empty.string() + ": empty file");

    std::string json = R"({"asset":{"version":"2.0"},"x":[})";
    std::string glb = "glTF";
    const auto u32 = [&glb](uint32_t v) {
      for (int shift = 0; shift < 32; shift += 8) glb += static_cast<char>((v >> shift) & 0xFF);
    };
    while (json.size() % 4) json += ' ';
    u32(2);
    u32(static_cast<uint32_t>(20 + json.size()));
    u32(static_cast<uint32_t>(json.size()));
    u32(0x4E4F534Au);
    glb += json;
    const fs::path binary = writeScratch("syntax.glb", glb);
    CHECK(contains(errorOf([&] { rt::loadGltfScene(binary); }),
                   binary.string() + ": GLB JSON chunk: byte 33: "));

    const fs::path overflow =
        writeScratch("overflow.gltf", R"({"asset":{"version":"2.0"},"x":[1e999]})");
    CHECK(errorOf([&] { rt::loadGltfScene(overflow); }) ==
          overflow.string() + ": byte 33: number overflow parsing '1e999'");

    const fs::path extension =
        writeScratch("extension.gltf",
                     R"({"asset":{"version":"2.0"},"extensionsRequired":["EXT_\n\u001b[31m"]})");
    const std::string required = errorOf([&] { rt::loadGltfScene(extension); });
    CHECK(isPrintableLine(required));
    CHECK(contains(required, "requires extension EXT_\\n\\x1B[31m"));
  }
}

TEST_SUITE("scene hostile gltf") {
  TEST_CASE("glTF: tinygltf's complaints about a property gain the object's path") {
    const std::string head = R"({"asset":{"version":"2.0"},)";
    const fs::path noLength = writeScratch(
        "nolength.gltf",
        head +
            R"("buffers":[{"byteLength":4,"uri":"data:application/octet-stream;base64,AAAAAA=="}],
        "bufferViews":[{"buffer":0,"byteLength":4},{"buffer":0}]})");
    CHECK(errorOf([&] { rt::loadGltfScene(noLength); }) ==
          noLength.string() + ": bufferViews[1].byteLength: missing (required)");
    const fs::path negative = writeScratch(
        "negative.gltf",
        head +
            R"("buffers":[{"byteLength":-5,"uri":"data:application/octet-stream;base64,AAAA"}]})");
    CHECK(errorOf([&] { rt::loadGltfScene(negative); }) ==
          negative.string() + ": buffers[0].byteLength: must be a non-negative integer, got -5");
    const fs::path noCount = writeScratch(
        "nocount.gltf", head + R"("accessors":[{"componentType":5126,"type":"VEC3"}]})");
    CHECK(errorOf([&] { rt::loadGltfScene(noCount); }) ==
          noCount.string() + ": accessors[0].count: missing (required)");
  }

  TEST_CASE("glTF: data URIs quoted by tinygltf are shortened") {
    const std::string data = "data:application/octet-stream;base64," + std::string(4000, 'Q');
    const fs::path file = writeScratch(
        "datauri.gltf",
        R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":9,"uri":")" + data + R"("}]})");
    const std::string error = errorOf([&] { rt::loadGltfScene(file); });
    CHECK(error.size() < 400);
    CHECK(contains(error, "data:application/octet-stream;base64,QQQQQQQQQQQ..."));
  }
}

TEST_SUITE("scene hostile vectors") {
  bool isUnit(const glm::vec3& v) { return std::abs(glm::length(v) - 1.0f) < 1e-5f; }

  TEST_CASE("normalizeInPlace: denormal and huge vectors become unit; zero and NaN do not") {
    for (glm::vec3 v : {glm::vec3(2.2e-39f, 2.3e-39f, 1.1e-39f), glm::vec3(1e-45f, 0.0f, 0.0f),
                        glm::vec3(3e38f, -3e38f, 3e38f), glm::vec3(0.0f, 3.0f, 4.0f)}) {
      CAPTURE(v.x);
      REQUIRE(rt::normalizeInPlace(v));
      CHECK(isUnit(v));
    }
    glm::vec3 both(2e-39f, 2e-39f, 0.0f);
    REQUIRE(rt::normalizeInPlace(both));
    CHECK(both.x == doctest::Approx(std::sqrt(0.5f)));
    for (glm::vec3 v : {glm::vec3(0.0f), glm::vec3(NAN, 1.0f, 0.0f), glm::vec3(INFINITY, 0, 0)}) {
      const glm::vec3 before = v;
      CHECK_FALSE(rt::normalizeInPlace(v));
      CHECK((v == before || std::isnan(v.x)));
    }
  }

  TEST_CASE("PLY: denormal normals load as unit normals; denormal faces get a unit fallback") {
    const std::string header =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const rt::TriangleMesh tiny = rt::parsePly(header +
                                                   "0 0 0 2.2e-39 2.3e-39 1.1e-39\n"
                                                   "1 0 0 0 0 1e-45\n"
                                                   "0 1 0 3e38 3e38 0\n3 0 1 2\n",
                                               "tiny.ply");
    for (const glm::vec3& n : tiny.normals) CHECK(isUnit(n));
    const rt::TriangleMesh fallback = rt::parsePly(header +
                                                       "0 0 0 0 0 0\n"
                                                       "1e-39 0 0 0 0 0\n"
                                                       "0 1e-39 0 0 0 0\n3 0 1 2\n",
                                                   "fallback.ply");
    for (const glm::vec3& n : fallback.normals) CHECK(isUnit(n));
  }

  TEST_CASE("JSON scenes: a denormal view direction or target offset gives a unit forward") {
    std::string scene = sceneWithShape(kSphere);
    scene.replace(scene.find("[0,0,-1]"), 8, "[1e-39,2e-39,-1e-39]");
    CHECK(isUnit(rt::parseJsonScene(scene, "tiny.json").camera.forward));
  }
}
