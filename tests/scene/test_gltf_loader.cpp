// Tests for rt::loadGltfScene / rt::appendGltf: hand-made glTF files for each
// feature and each kind of broken input; Khronos sample models with known
// facts; every file of shared/assets/gltf-invalid (each must load or fail with
// one clear line, in bounded time and memory, without crashing); and a few
// small renders to look at.
#include <doctest/doctest.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "formats/gltf/GltfLoader.hpp"
#include "render/Renderer.hpp"
#include "support/Glb.hpp"
#include "support/JsonMutations.hpp"
#include "support/TestSupport.hpp"
#include "util/Clock.hpp"
#include "util/Error.hpp"

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

bool near(glm::vec3 a, glm::vec3 b, float tolerance = 1e-4f) {
  return glm::length(a - b) < tolerance;
}

glm::vec3 place(const glm::mat4& m, glm::vec3 p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }
glm::vec3 place(const rt::WorldTransform& m, glm::vec3 p) { return place(glm::mat4(m), p); }
bool near(const glm::dvec3& a, glm::vec3 b, float tolerance = 1e-4f) {
  return near(glm::vec3(a), b, tolerance);
}

// ------------------------------------------------------------ scene queries

size_t uniqueTriangles(const rt::Scene& scene) {
  size_t n = 0;
  for (const rt::TriangleMesh& mesh : scene.meshes) n += mesh.faces.size();
  return n;
}

size_t drawnTriangles(const rt::Scene& scene) {
  size_t n = 0;
  for (const rt::Shape& shape : scene.shapes) {
    if (const auto* instance = std::get_if<rt::MeshInstance>(&shape.geometry)) {
      n += scene.meshes.at(instance->mesh).faces.size();
    }
  }
  return n;
}

const rt::MeshInstance& instanceOf(const rt::Scene& scene, size_t shape) {
  return std::get<rt::MeshInstance>(scene.shapes.at(shape).geometry);
}

const rt::TriangleMesh& meshOf(const rt::Scene& scene, size_t shape) {
  return scene.meshes.at(instanceOf(scene, shape).mesh);
}

struct Box3 {
  glm::vec3 lo{1e30f}, hi{-1e30f};
  void grow(glm::vec3 p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
};

// World-space bounds of every placed vertex.
Box3 worldBounds(const rt::Scene& scene) {
  Box3 box;
  for (size_t i = 0; i < scene.shapes.size(); ++i) {
    for (glm::vec3 p : meshOf(scene, i).positions)
      box.grow(place(instanceOf(scene, i).objectToWorld, p));
  }
  return box;
}

// The world-space winding normal of face `face` of shape `shape`.
glm::vec3 windingNormal(const rt::Scene& scene, size_t shape, size_t face = 0) {
  const rt::TriangleMesh& mesh = meshOf(scene, shape);
  const glm::mat4 m(instanceOf(scene, shape).objectToWorld);
  glm::uvec3 f = mesh.faces.at(face);
  glm::vec3 a = place(m, mesh.positions[f.x]);
  glm::vec3 b = place(m, mesh.positions[f.y]);
  glm::vec3 c = place(m, mesh.positions[f.z]);
  return glm::normalize(glm::cross(b - a, c - a));
}

bool hasWarning(const rt::Scene& scene, const std::string& part) {
  return std::any_of(scene.warnings.begin(), scene.warnings.end(),
                     [&](const std::string& line) { return contains(line, part); });
}

std::string summary(const rt::Scene& scene) {
  return std::to_string(drawnTriangles(scene)) + " triangles drawn (" +
         std::to_string(uniqueTriangles(scene)) + " stored in " +
         std::to_string(scene.meshes.size()) + " meshes, " + std::to_string(scene.shapes.size()) +
         " instances), " + std::to_string(scene.materials.size()) + " materials, " +
         std::to_string(scene.textures.size()) + " textures, " +
         std::to_string(scene.warnings.size()) + " warnings";
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// What the renderer relies on: indices in range, no degenerate or empty
// meshes, unit normals, finite numbers, invertible placements.
std::string unsoundness(const rt::Scene& scene) {
  for (const rt::TriangleMesh& mesh : scene.meshes) {
    size_t n = mesh.positions.size();
    if (mesh.faces.empty()) return "empty mesh";
    if (!mesh.normals.empty() && mesh.normals.size() != n) return "normal count";
    if (!mesh.uvs.empty() && mesh.uvs.size() != n) return "uv count";
    for (glm::uvec3 f : mesh.faces) {
      if (f.x >= n || f.y >= n || f.z >= n) return "face index";
      if (f.x == f.y || f.y == f.z || f.x == f.z) return "degenerate face";
    }
    for (glm::vec3 p : mesh.positions) {
      if (!finite(p)) return "position";
    }
    for (glm::vec3 normal : mesh.normals) {
      if (!finite(normal) || std::abs(glm::length(normal) - 1.0f) > 1e-3f) return "normal";
    }
    for (glm::vec2 uv : mesh.uvs) {
      if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return "uv";
    }
  }
  for (size_t i = 0; i < scene.shapes.size(); ++i) {
    if (scene.shapes[i].material >= scene.materials.size()) return "material index";
    const glm::mat4 m(instanceOf(scene, i).objectToWorld);
    if (instanceOf(scene, i).mesh >= scene.meshes.size()) return "mesh index";
    for (int c = 0; c < 4; ++c) {
      if (!finite(glm::vec3(m[c])) || !std::isfinite(m[c][3])) return "matrix";
    }
    if (glm::determinant(glm::mat3(m)) == 0.0f) return "singular matrix";
  }
  for (const rt::Material& material : scene.materials) {
    if (material.diffuseTexture >= int(scene.textures.size())) return "texture index";
    if (!finite(material.diffuseColor) || !std::isfinite(material.ks) || material.ior < 1.0f ||
        !(material.specularExponent >= 1.0f)) {
      return "material values";
    }
  }
  for (const rt::PointLight& light : scene.pointLights) {
    if (!finite(glm::vec3(light.position)) || !finite(light.diffuseIntensity)) return "light";
  }
  const rt::Camera& camera = scene.camera;
  if (!finite(glm::vec3(camera.position)) || !finite(camera.forward) || !finite(camera.up))
    return "camera";
  if (!(camera.fovYDegrees > 0.0f && camera.fovYDegrees < 180.0f)) return "camera fov";
  if (camera.width < 1 || camera.width > 16384 || camera.height < 1) return "camera size";
  return "";
}

// The rt::Error message of loading `file`, or "" when it loads.
std::string errorOf(const fs::path& file) {
  try {
    rt::loadGltfScene(file);
  } catch (const rt::Error& error) {
    std::string message = error.what();
    CHECK_MESSAGE(!contains(message, "\n"), "error messages are one line: " << message);
    CHECK_MESSAGE(message.rfind(file.string() + ": ", 0) == 0, "names the file: " << message);
    return message;
  }
  return "";
}

// ------------------------------------------------------ hand-made glTF files

std::string base64(const std::vector<uint8_t>& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t chunk = uint32_t(bytes[i]) << 16;
    if (i + 1 < bytes.size()) chunk |= uint32_t(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) chunk |= bytes[i + 2];
    out += digits[(chunk >> 18) & 63];
    out += digits[(chunk >> 12) & 63];
    out += i + 1 < bytes.size() ? digits[(chunk >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? digits[chunk & 63] : '=';
  }
  return out;
}

// A glTF document under construction, with one binary buffer.
struct GltfBuilder {
  Json doc = Json::parse(R"({"asset": {"version": "2.0"}, "scene": 0,
                             "scenes": [{"nodes": []}], "nodes": [], "meshes": [],
                             "accessors": [], "bufferViews": []})");
  std::vector<uint8_t> bin;

  template <typename T>
  int view(const std::vector<T>& values, size_t stride = 0) {
    while (bin.size() % 4) bin.push_back(0);
    Json v = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", values.size() * sizeof(T)}};
    if (stride) v["byteStride"] = stride;
    const auto* bytes = reinterpret_cast<const uint8_t*>(values.data());
    bin.insert(bin.end(), bytes, bytes + values.size() * sizeof(T));
    doc["bufferViews"].push_back(v);
    return int(doc["bufferViews"].size() - 1);
  }
  int accessor(int view, int componentType, size_t count, const char* type, size_t offset = 0) {
    doc["accessors"].push_back({{"bufferView", view},
                                {"componentType", componentType},
                                {"count", count},
                                {"type", type},
                                {"byteOffset", offset}});
    return int(doc["accessors"].size() - 1);
  }
  int floats(const std::vector<float>& values, const char* type, size_t components) {
    return accessor(view(values), 5126, values.size() / components, type);
  }
  int positions(const std::vector<float>& xyz) { return floats(xyz, "VEC3", 3); }
  int indices16(const std::vector<uint16_t>& values) {
    return accessor(view(values), 5123, values.size(), "SCALAR");
  }
  int mesh(Json primitive) {
    doc["meshes"].push_back({{"primitives", Json::array({primitive})}});
    return int(doc["meshes"].size() - 1);
  }
  int node(Json node, bool root = true) {
    doc["nodes"].push_back(node);
    int index = int(doc["nodes"].size() - 1);
    if (root) doc["scenes"][0]["nodes"].push_back(index);
    return index;
  }
  // The document with the buffer embedded as a data URI.
  Json embedded() const {
    Json out = doc;
    out["buffers"] = {{{"byteLength", bin.size()},
                       {"uri", "data:application/octet-stream;base64," + base64(bin)}}};
    return out;
  }
};

fs::path scratchDir() {
  fs::path dir = fs::path(RT_TEST_OUTPUT_DIR) / "gltf";
  fs::create_directories(dir);
  return dir;
}

fs::path writeBytes(const std::string& name, const std::string& bytes) {
  fs::path file = scratchDir() / name;
  std::ofstream(file, std::ios::binary) << bytes;
  return file;
}

fs::path writeGltf(const std::string& name, const Json& doc) {
  return writeBytes(name, doc.dump());
}

// A GLB of the builder's document, its buffer in the BIN chunk.
std::string glbBytes(const GltfBuilder& b) { return rt::test::glbBytes(b.doc, b.bin); }

// A unit right triangle in the z = 0 plane, counter-clockwise seen from +z.
GltfBuilder triangleModel() {
  GltfBuilder b;
  int pos = b.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  int idx = b.indices16({0, 1, 2});
  int mesh = b.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}});
  b.node({{"mesh", mesh}});
  return b;
}

rt::Scene loadDoc(const std::string& name, const Json& doc) {
  return rt::loadGltfScene(writeGltf(name, doc));
}

std::string errorOfDoc(const std::string& name, const Json& doc) {
  return errorOf(writeGltf(name, doc));
}

// A 2x2 PNG next to the hand-made files.
void writeTexture(const std::string& name) {
  rt::ImageF image{2, 2, {1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1, 1, 1, 1, 1}};
  rt::writeImage(scratchDir() / name, image, {});
}

// One triangle with texture coordinates for each of `materials`, whose
// texture 0 is tex.png (writeTexture); tests add samplers and textures.
GltfBuilder texturedTriangles(const Json& materials) {
  writeTexture("tex.png");
  GltfBuilder b;
  int pos = b.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  int uv0 = b.floats({1, 0, 0, 1, 1, 1}, "VEC2", 2);
  b.doc["images"] = {{{"uri", "tex.png"}}};
  b.doc["textures"] = {{{"source", 0}}};
  b.doc["materials"] = materials;
  Json attributes = {{"POSITION", pos}, {"TEXCOORD_0", uv0}};
  for (int material = 0; material < int(materials.size()); ++material) {
    b.node({{"mesh", b.mesh({{"attributes", attributes}, {"material", material}})}});
  }
  return b;
}

// ---------------------------------------------------------------- shared data

fs::path assetDir(const char* sub) { return rt::test::requireShared() / "assets" / sub; }

fs::path sample(const char* relative) { return assetDir("gltf/khronos-sample-assets") / relative; }

std::vector<fs::path> gltfFilesUnder(const fs::path& folder) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    std::string ext = entry.path().extension().string();
    if (entry.is_regular_file() && (ext == ".gltf" || ext == ".glb")) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

bool sameMeshes(const rt::Scene& a, const rt::Scene& b) {
  if (a.meshes.size() != b.meshes.size() || a.shapes.size() != b.shapes.size()) return false;
  for (size_t i = 0; i < a.meshes.size(); ++i) {
    const rt::TriangleMesh& x = a.meshes[i];
    const rt::TriangleMesh& y = b.meshes[i];
    if (x.positions != y.positions || x.faces != y.faces || x.normals != y.normals ||
        x.uvs != y.uvs) {
      return false;
    }
  }
  for (size_t i = 0; i < a.shapes.size(); ++i) {
    if (instanceOf(a, i).objectToWorld != instanceOf(b, i).objectToWorld) return false;
  }
  return true;
}

// ------------------------------------------------- isolated loads (invalid files)

// How loading a file in a child process ended.
struct Outcome {
  enum Kind { Loaded, Rejected, OtherException, Crashed, TimedOut } kind = Crashed;
  std::string text;  // summary, rt::Error message, or what went wrong
  double seconds = 0;
};

size_t addressSpaceBytes() {
  std::ifstream statm("/proc/self/statm");
  size_t pages = 0;
  statm >> pages;
  return pages * size_t(sysconf(_SC_PAGESIZE));
}

// Reads what the child writes until it closes the pipe or time runs out.
bool readUntilClosed(int fd, std::chrono::steady_clock::time_point deadline, std::string& out) {
  for (;;) {
    auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                    deadline - std::chrono::steady_clock::now())
                    .count();
    pollfd pfd{fd, POLLIN, 0};
    if (left <= 0 || poll(&pfd, 1, int(left)) <= 0) return false;
    char buffer[4096];
    ssize_t n = read(fd, buffer, sizeof buffer);
    if (n <= 0) return true;
    out.append(buffer, size_t(n));
  }
}

// Runs loadGltfScene in a forked child with a time limit and an address-space
// limit (2 GiB above the parent's), so that a crash, hang or runaway
// allocation is reported as such instead of taking the test run down.
Outcome loadIsolated(const fs::path& file, int timeoutSeconds) {
  int fds[2];
  REQUIRE(pipe(fds) == 0);
  size_t limit = addressSpaceBytes() + (size_t(2) << 30);
  auto start = rt::SteadyClock::now();
  pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    close(fds[0]);
    rlimit addressSpace{limit, limit};
    setrlimit(RLIMIT_AS, &addressSpace);
    std::string message;
    try {
      rt::Scene scene = rt::loadGltfScene(file);
      std::string problem = unsoundness(scene);
      message = problem.empty() ? "L" + summary(scene) : "Xunsound scene: " + problem;
    } catch (const rt::Error& error) {
      message = "R" + std::string(error.what());
    } catch (const std::exception& error) {
      message = "X" + std::string(error.what());
    }
    ssize_t written = write(fds[1], message.data(), message.size());
    _exit(written == ssize_t(message.size()) ? 0 : 1);
  }
  close(fds[1]);
  std::string message;
  bool finished = readUntilClosed(fds[0], start + std::chrono::seconds(timeoutSeconds), message);
  close(fds[0]);
  if (!finished) kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  Outcome outcome;
  outcome.seconds = rt::secondsSince(start);
  if (!finished) {
    outcome.kind = Outcome::TimedOut;
  } else if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || message.empty()) {
    outcome.kind = Outcome::Crashed;
    outcome.text = WIFSIGNALED(status) ? "signal " + std::to_string(WTERMSIG(status)) : "no result";
  } else {
    outcome.kind = message[0] == 'L'   ? Outcome::Loaded
                   : message[0] == 'R' ? Outcome::Rejected
                                       : Outcome::OtherException;
    outcome.text = message.substr(1);
  }
  return outcome;
}

// The kind of an error message: the text after the file name with numbers
// replaced by '#', so that messages group into classes.
std::string messageClass(const std::string& message, const fs::path& file) {
  std::string rest = message.substr(std::min(message.size(), file.string().size() + 2));
  std::string out;
  for (char c : rest) {
    bool digit = c >= '0' && c <= '9';
    if (digit && !out.empty() && out.back() == '#') continue;
    out += digit ? '#' : c;
  }
  return out.substr(0, 90);
}

}  // namespace

TEST_SUITE("scene gltf") {
  TEST_CASE("a lone triangle gets a default camera framing it and a default light") {
    rt::Scene scene = loadDoc("triangle.gltf", triangleModel().embedded());
    CHECK(scene.conventions == rt::Conventions::Textbook);
    CHECK(near(scene.backgroundColor, glm::vec3(0.5f)));
    REQUIRE(scene.meshes.size() == 1);
    REQUIRE(scene.shapes.size() == 1);
    CHECK(scene.meshes[0].faces == std::vector<glm::uvec3>{{0, 1, 2}});
    CHECK(scene.meshes[0].positions[1] == glm::vec3(1, 0, 0));
    CHECK(scene.warnings.empty());
    const rt::Camera& camera = scene.camera;
    CHECK(camera.width == 800);
    CHECK(camera.height == 600);
    CHECK(camera.fovYDegrees == doctest::Approx(45.0));
    CHECK(near(camera.forward, -glm::normalize(glm::vec3(0, 0.5f, 1))));
    glm::vec3 center(0.5f, 0.5f, 0.0f);
    const glm::vec3 position(camera.position);
    CHECK(glm::length(glm::cross(center - position, camera.forward)) < 1e-4f);
    for (glm::vec3 corner : scene.meshes[0].positions) {
      float angle =
          glm::degrees(std::acos(glm::dot(glm::normalize(corner - position), camera.forward)));
      CHECK(angle < 22.5f);
    }
    REQUIRE(scene.pointLights.size() == 1);
    CHECK(scene.pointLights[0].diffuseIntensity == glm::vec3(1.0f));
    glm::vec3 offset(scene.pointLights[0].position - camera.position);
    CHECK(glm::dot(offset, glm::vec3(0, 1, 0)) > 0.0f);  // above the camera
    CHECK(offset.x > 0.0f);                              // and to its right
  }

  TEST_CASE(".gltf with an embedded buffer and .glb read the same") {
    GltfBuilder b = triangleModel();
    rt::Scene fromGltf = loadDoc("same.gltf", b.embedded());
    rt::Scene fromGlb = rt::loadGltfScene(writeBytes("same.glb", glbBytes(b)));
    rt::Scene fromMislabelled = rt::loadGltfScene(writeBytes("glb-named.gltf", glbBytes(b)));
    CHECK(sameMeshes(fromGltf, fromGlb));
    CHECK(sameMeshes(fromGltf, fromMislabelled));
  }

  TEST_CASE("indices of 8, 16 and 32 bits read the same") {
    for (int type : {5121, 5123, 5125}) {
      CAPTURE(type);
      GltfBuilder b;
      int pos = b.positions({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
      std::vector<uint32_t> quad = {0, 1, 2, 0, 2, 3};
      int view = type == 5121   ? b.view(std::vector<uint8_t>(quad.begin(), quad.end()))
                 : type == 5123 ? b.view(std::vector<uint16_t>(quad.begin(), quad.end()))
                                : b.view(quad);
      int idx = b.accessor(view, type, 6, "SCALAR");
      b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}})}});
      rt::Scene scene = loadDoc("indices.gltf", b.embedded());
      CHECK(scene.meshes.at(0).faces == std::vector<glm::uvec3>{{0, 1, 2}, {0, 2, 3}});
    }
  }

  TEST_CASE("interleaved attributes honour the byte stride") {
    GltfBuilder b;
    // position xyz, normal xyz per vertex: 24 bytes apart.
    int view = b.view(std::vector<float>{0, 0, 0, 0, 0, 2, 1, 0, 0, 0, 0, 2, 0, 1, 0, 0, 0, 2}, 24);
    int pos = b.accessor(view, 5126, 3, "VEC3", 0);
    int nrm = b.accessor(view, 5126, 3, "VEC3", 12);
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}})}});
    rt::Scene scene = loadDoc("interleaved.gltf", b.embedded());
    const rt::TriangleMesh& mesh = scene.meshes.at(0);
    CHECK(mesh.positions == std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    CHECK(mesh.normals == std::vector<glm::vec3>(3, {0, 0, 1}));  // normalised on load
    CHECK(mesh.faces == std::vector<glm::uvec3>{{0, 1, 2}});      // no indices: 0, 1, 2
  }

  TEST_CASE("normalized integer attributes (KHR_mesh_quantization)") {
    GltfBuilder b;
    b.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
    b.doc["extensionsUsed"] = {"KHR_mesh_quantization"};
    // SHORT positions padded to 8 bytes; UNSIGNED_BYTE uvs padded to 4.
    int posView = b.view(std::vector<int16_t>{0, 0, 0, 0, 32767, -32768, 0, 0, 0, 16384, 0, 0}, 8);
    int pos = b.accessor(posView, 5122, 3, "VEC3");
    b.doc["accessors"][pos]["normalized"] = true;
    int uvView = b.view(std::vector<uint8_t>{0, 255, 0, 0, 255, 0, 0, 0, 51, 102, 0, 0}, 4);
    int uv = b.accessor(uvView, 5121, 3, "VEC2");
    b.doc["accessors"][uv]["normalized"] = true;
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv}}}})}});
    rt::Scene scene = loadDoc("quantized.gltf", b.embedded());
    const rt::TriangleMesh& mesh = scene.meshes.at(0);
    CHECK(near(mesh.positions[1], {1, -1, 0}));  // -32768 clamps to -1
    CHECK(near(mesh.positions[2], {0, 16384.0f / 32767.0f, 0}));
    CHECK(mesh.uvs == std::vector<glm::vec2>{{0, 1}, {1, 0}, {0.2f, 0.4f}});
  }

  TEST_CASE("COLOR_0: RGB floats or RGBA normalized bytes, linear, clamped; all white is none") {
    auto load = [](auto values, int componentType, const char* type, bool normalized) {
      GltfBuilder b;
      int pos = b.accessor(b.view(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0}), 5126, 3, "VEC3");
      int color = b.accessor(b.view(values), componentType, 3, type);
      if (normalized) b.doc["accessors"][color]["normalized"] = true;
      b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", pos}, {"COLOR_0", color}}}})}});
      return loadDoc("colours.gltf", b.embedded());
    };
    rt::Scene floats = load(std::vector<float>{1, 0, 0.5f, 0, 2, 0, -1, 0, 1}, 5126, "VEC3", false);
    CHECK(floats.meshes.at(0).colors ==
          std::vector<glm::vec3>{{1, 0, 0.5f}, {0, 1, 0}, {0, 0, 1}});  // linear, clamped
    CHECK(floats.warnings.empty());
    rt::Scene bytes =
        load(std::vector<uint8_t>{255, 0, 0, 7, 0, 255, 0, 255, 0, 0, 51, 0}, 5121, "VEC4", true);
    CHECK(bytes.meshes.at(0).colors == std::vector<glm::vec3>{{1, 0, 0}, {0, 1, 0}, {0, 0, 0.2f}});
    rt::Scene white = load(std::vector<float>{1, 1, 1, 1, 1, 1, 1, 1, 1}, 5126, "VEC3", false);
    CHECK(white.meshes.at(0).colors.empty());
  }

  TEST_CASE("sparse accessors replace elements, with or without a base buffer view") {
    GltfBuilder b;
    int pos = b.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    int indices = b.view(std::vector<uint16_t>{2, 0});
    int values = b.view(std::vector<float>{0, 2, 0});
    b.doc["accessors"][pos]["sparse"] = {
        {"count", 1},
        {"indices", {{"bufferView", indices}, {"componentType", 5123}}},
        {"values", {{"bufferView", values}}}};
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", pos}}}})}});
    int all = b.view(std::vector<uint8_t>{0, 1, 2, 0});
    int triangle = b.view(std::vector<float>{0, 0, 1, 1, 0, 1, 0, 1, 1});
    b.doc["accessors"].push_back({{"componentType", 5126},
                                  {"count", 3},
                                  {"type", "VEC3"},
                                  {"sparse",
                                   {{"count", 3},
                                    {"indices", {{"bufferView", all}, {"componentType", 5121}}},
                                    {"values", {{"bufferView", triangle}}}}}});
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", pos + 1}}}})}});
    rt::Scene scene = loadDoc("sparse.gltf", b.embedded());
    REQUIRE(scene.meshes.size() == 2);
    CHECK(scene.meshes[0].positions == std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {0, 2, 0}});
    CHECK(scene.meshes[1].positions == std::vector<glm::vec3>{{0, 0, 1}, {1, 0, 1}, {0, 1, 1}});
  }

  TEST_CASE("triangle strips and fans follow the specification's vertex order") {
    GltfBuilder b;
    int pos = b.positions({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 2, 0});
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", pos}}}, {"mode", 5}})}});
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", pos}}}, {"mode", 6}})}});
    int repeated = b.indices16({0, 1, 2, 2, 3, 4});  // a degenerate joint
    b.node({{"mesh",
             b.mesh({{"attributes", {{"POSITION", pos}}}, {"mode", 5}, {"indices", repeated}})}});
    rt::Scene scene = loadDoc("strips.gltf", b.embedded());
    REQUIRE(scene.meshes.size() == 3);
    CHECK(scene.meshes[0].faces == std::vector<glm::uvec3>{{0, 1, 2}, {1, 3, 2}, {2, 3, 4}});
    CHECK(scene.meshes[1].faces == std::vector<glm::uvec3>{{1, 2, 0}, {2, 3, 0}, {3, 4, 0}});
    CHECK(scene.meshes[2].faces == std::vector<glm::uvec3>{{0, 1, 2}, {2, 4, 3}});
    // The strip's alternation keeps every face of this zigzag facing +z.
    for (size_t f = 0; f < 3; ++f) CHECK(near(windingNormal(scene, 0, f), {0, 0, 1}));
  }

  TEST_CASE("points and lines are skipped with a warning") {
    GltfBuilder b;
    int pos = b.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", pos}}}, {"mode", 1}})}});
    rt::Scene scene = loadDoc("lines.gltf", b.embedded());
    CHECK(scene.shapes.empty());
    CHECK(hasWarning(
        scene, "points and lines (primitive modes 0 to 3) ignored (meshes[0].primitives[0])"));
    CHECK(hasWarning(scene, "nothing to draw"));
  }

  TEST_CASE("node matrices and TRS give the same transforms, composed down the tree") {
    glm::dquat rotation = glm::angleAxis(glm::radians(90.0), glm::dvec3(0, 1, 0));
    glm::dmat4 trs = glm::translate(glm::dmat4(1.0), glm::dvec3(1, 2, 3)) *
                     glm::mat4_cast(rotation) * glm::scale(glm::dmat4(1.0), glm::dvec3(2, 3, 4));
    GltfBuilder b = triangleModel();  // node 0: the triangle at the root
    std::vector<double> matrix(&trs[0][0], &trs[0][0] + 16);
    b.node({{"mesh", 0}, {"matrix", matrix}});
    b.node({{"mesh", 0},
            {"translation", {1, 2, 3}},
            {"rotation", {rotation.x, rotation.y, rotation.z, rotation.w}},
            {"scale", {2, 3, 4}}});
    int child = b.node({{"mesh", 0}, {"translation", {0, 0, 5}}}, false);
    b.node({{"children", {child}}, {"matrix", matrix}});
    rt::Scene scene = loadDoc("transforms.gltf", b.embedded());
    REQUIRE(scene.shapes.size() == 4);
    glm::mat4 expected(trs);
    for (size_t shape : {1, 2}) {
      for (int c = 0; c < 4; ++c) {
        CHECK(near(glm::vec3(glm::mat4(instanceOf(scene, shape).objectToWorld)[c]),
                   glm::vec3(expected[c])));
      }
    }
    glm::mat4 nested = expected * glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 5));
    CHECK(near(place(instanceOf(scene, 3).objectToWorld, {1, 0, 0}), place(nested, {1, 0, 0})));
  }

  TEST_CASE("a mesh on several nodes is stored once; mirroring nodes get a reversed copy") {
    GltfBuilder b;
    int pos = b.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    int nrm = b.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
    int mesh = b.mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}});
    b.node({{"mesh", mesh}});
    b.node({{"mesh", mesh}, {"translation", {2, 0, 0}}});
    b.node({{"mesh", mesh}, {"scale", {-1, 1, 1}}});
    b.node({{"mesh", mesh}, {"scale", {-1, 1, 1}}, {"translation", {0, 3, 0}}});
    rt::Scene scene = loadDoc("instances.gltf", b.embedded());
    REQUIRE(scene.shapes.size() == 4);
    CHECK(scene.meshes.size() == 2);
    CHECK(instanceOf(scene, 0).mesh == instanceOf(scene, 1).mesh);
    CHECK(instanceOf(scene, 2).mesh == instanceOf(scene, 3).mesh);
    CHECK(instanceOf(scene, 0).mesh != instanceOf(scene, 2).mesh);
    CHECK(scene.meshes[instanceOf(scene, 2).mesh].faces == std::vector<glm::uvec3>{{0, 2, 1}});
    // Winding and normals (transformed by the inverse transpose) agree everywhere.
    for (size_t shape = 0; shape < 4; ++shape) {
      CAPTURE(shape);
      glm::mat3 normalMatrix = glm::transpose(
          glm::inverse(glm::mat3(glm::mat4(instanceOf(scene, shape).objectToWorld))));
      glm::vec3 normal = glm::normalize(normalMatrix * meshOf(scene, shape).normals[0]);
      CHECK(near(windingNormal(scene, shape), normal));
      CHECK(near(normal, {0, 0, 1}));
    }
  }

  TEST_CASE("EXT_mesh_gpu_instancing places one stored mesh many times") {
    GltfBuilder b = triangleModel();
    b.doc["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
    int t = b.floats({0, 0, 0, 5, 0, 0, 0, 5, 0}, "VEC3", 3);
    int s = b.floats({1, 1, 1, 2, 2, 2, -1, 1, 1}, "VEC3", 3);
    b.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"] = {{"TRANSLATION", t},
                                                                                {"SCALE", s}};
    b.doc["nodes"][0]["translation"] = {0, 0, 10};
    rt::Scene scene = loadDoc("gpu-instancing.gltf", b.embedded());
    REQUIRE(scene.shapes.size() == 3);
    CHECK(scene.meshes.size() == 2);  // the third instance mirrors
    CHECK(near(place(instanceOf(scene, 1).objectToWorld, {1, 0, 0}), {7, 0, 10}));
    CHECK(near(place(instanceOf(scene, 2).objectToWorld, {1, 0, 0}), {-1, 5, 10}));
    CHECK(near(windingNormal(scene, 2), {0, 0, 1}));
  }

  TEST_CASE("KHR_lights_punctual: normalised, spot and directional lights become point lights") {
    GltfBuilder b = triangleModel();
    b.doc["extensionsUsed"] = {"KHR_lights_punctual"};
    b.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
        {{"type", "point"}, {"color", {1, 0.5, 0}}, {"intensity", 10}},
        {{"type", "spot"}, {"intensity", 5}, {"spot", {{"outerConeAngle", 0.5}}}},
        {{"type", "directional"}, {"intensity", 2}}};
    auto light = [](int index) { return Json{{"KHR_lights_punctual", {{"light", index}}}}; };
    b.node({{"translation", {0, 0, 4}}, {"extensions", light(0)}});
    b.node({{"translation", {1, 2, 3}}, {"extensions", light(1)}});
    // Rotated -90 degrees about x: the light shines down (-z becomes -y).
    double h = std::sqrt(0.5);
    b.node({{"rotation", {-h, 0, 0, h}}, {"extensions", light(2)}});
    rt::Scene scene = loadDoc("lights.gltf", b.embedded());
    REQUIRE(scene.pointLights.size() == 3);
    CHECK(near(scene.pointLights[0].position, {0, 0, 4}));
    CHECK(near(scene.pointLights[0].diffuseIntensity, {1, 0.5f, 0}));
    CHECK(near(scene.pointLights[0].specularIntensity, {1, 0.5f, 0}));
    CHECK(near(scene.pointLights[1].position, {1, 2, 3}));
    CHECK(near(scene.pointLights[1].diffuseIntensity, glm::vec3(0.5f)));
    float radius = 0.5f * std::sqrt(2.0f);  // of the triangle's bounding box
    CHECK(near(scene.pointLights[2].position, {0.5f, 0.5f + 100.0f * radius, 0.0f}, 1e-3f));
    CHECK(near(scene.pointLights[2].diffuseIntensity, glm::vec3(0.2f)));
    CHECK(hasWarning(scene, "spot light cones"));
    CHECK(hasWarning(scene, "directional lights (placed as distant point lights)"));
  }

  TEST_CASE("KHR_materials_volume: a thickness makes glass solid; attenuation is ignored") {
    GltfBuilder b = triangleModel();
    b.doc["extensionsUsed"] = {"KHR_materials_transmission", "KHR_materials_volume"};
    b.doc["extensionsRequired"] = {"KHR_materials_volume"};
    Json transmission = {{"KHR_materials_transmission", {{"transmissionFactor", 1}}}};
    Json solid = transmission;
    solid["KHR_materials_volume"] = {
        {"thicknessFactor", 0.5}, {"attenuationColor", {1, 0.5, 0.5}}, {"attenuationDistance", 2}};
    Json zero = transmission;
    zero["KHR_materials_volume"] = {{"thicknessFactor", 0}};
    b.doc["materials"] = {
        {{"extensions", transmission}}, {{"extensions", solid}}, {{"extensions", zero}}};
    for (int m = 0; m < 3; ++m) {
      Json primitive = b.doc["meshes"][0]["primitives"][0];
      primitive["material"] = m;
      b.node({{"mesh", b.mesh(primitive)}});
    }
    rt::Scene scene = loadDoc("volume.gltf", b.embedded());
    // shapes[0] is the model's own triangle, without a material.
    CHECK(scene.materials[scene.shapes[1].material].thinWalled);
    CHECK_FALSE(scene.materials[scene.shapes[2].material].thinWalled);
    CHECK(scene.materials[scene.shapes[3].material].thinWalled);  // a thickness of 0: thin
    CHECK(hasWarning(scene, "volume attenuation (KHR_materials_volume) ignored"));
  }

  TEST_CASE("metallic-roughness, transmission and ior onto Blinn-Phong") {
    GltfBuilder b = triangleModel();
    b.doc["extensionsUsed"] = {"KHR_materials_transmission", "KHR_materials_ior"};
    b.doc["materials"] = {
        {{"pbrMetallicRoughness",
          {{"baseColorFactor", {0.2, 0.4, 0.6, 1}},
           {"metallicFactor", 0},
           {"roughnessFactor", 0.5}}}},
        {{"pbrMetallicRoughness",
          {{"baseColorFactor", {1, 0.8, 0.2, 1}}, {"metallicFactor", 1}, {"roughnessFactor", 0}}}},
        {{"pbrMetallicRoughness", {{"metallicFactor", 0}, {"roughnessFactor", 0}}},
         {"extensions",
          {{"KHR_materials_transmission", {{"transmissionFactor", 1}}},
           {"KHR_materials_ior", {{"ior", 1.33}}}}}},
        Json::object()};
    for (int m = 0; m < 4; ++m) {
      Json primitive = b.doc["meshes"][0]["primitives"][0];
      primitive["material"] = m;
      b.node({{"mesh", b.mesh(primitive)}});
    }
    rt::Scene scene = loadDoc("materials.gltf", b.embedded());
    REQUIRE(scene.materials.size() == 5);
    const rt::Material& none = scene.materials[scene.shapes[0].material];  // no material
    CHECK(near(none.diffuseColor, glm::vec3(0.8f)));
    CHECK(none.kd == 1.0f);
    CHECK(none.ks == 0.0f);
    const rt::Material& plastic = scene.materials[scene.shapes[1].material];
    CHECK(near(plastic.diffuseColor, {0.2f, 0.4f, 0.6f}));
    CHECK(plastic.kd == doctest::Approx(1.0));
    CHECK(plastic.specularExponent == doctest::Approx(30.0));  // 2 / 0.5^4 - 2
    CHECK(plastic.ks == doctest::Approx(0.04 * 38.0 / (8.0 * glm::pi<double>())));
    CHECK(near(plastic.specularColor, glm::vec3(1.0f)));
    CHECK(plastic.reflectivity == 0.0f);
    CHECK(plastic.ior == doctest::Approx(1.5));
    const rt::Material& gold = scene.materials[scene.shapes[2].material];
    CHECK(gold.kd == 0.0f);
    CHECK(gold.ks == 1.0f);
    CHECK(gold.specularExponent == 10000.0f);
    CHECK(gold.reflectivity == 1.0f);
    CHECK(near(gold.specularColor, {1, 0.8f, 0.2f}));
    const rt::Material& glass = scene.materials[scene.shapes[3].material];
    CHECK(glass.transmission == 1.0f);
    CHECK(glass.ior == doctest::Approx(1.33));
    CHECK(glass.kd == 0.0f);
    CHECK(glass.tintedTransmission);  // glTF's transmitted light takes the base colour
    CHECK(glass.thinWalled);          // no KHR_materials_volume: glTF's thin-walled default
    const rt::Material& defaults = scene.materials[scene.shapes[4].material];  // metal, rough
    CHECK(defaults.kd == 0.0f);
    CHECK(defaults.specularExponent == 1.0f);
    CHECK(defaults.ks == doctest::Approx(9.0 / (8.0 * glm::pi<double>())));
    CHECK(defaults.reflectivity == 0.0f);
  }

  TEST_CASE("an emissive material makes its shapes area lights of its radiance") {
    writeTexture("glow.png");
    GltfBuilder b = triangleModel();  // a right triangle of area 1/2
    b.doc["extensionsUsed"] = {"KHR_materials_emissive_strength"};
    b.doc["images"] = {{{"uri", "glow.png"}}};
    b.doc["textures"] = {{{"source", 0}}};
    b.doc["materials"] = {
        {{"emissiveFactor", {1, 0.5, 0.25}},
         {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4}}}}}},
        {{"emissiveFactor", {1, 1, 1}}, {"emissiveTexture", {{"index", 0}}}}};
    for (int m = 0; m < 2; ++m) {
      Json primitive = b.doc["meshes"][0]["primitives"][0];
      primitive["material"] = m;
      b.node({{"mesh", b.mesh(primitive)}});
    }
    rt::Scene scene = loadDoc("glowing.gltf", b.embedded());
    REQUIRE(scene.areaLights.size() == 1);
    const rt::AreaLight& light = scene.areaLights[0];
    CHECK(light.shape == 1);  // shape 0: the model's own triangle, without a material
    // Radiance L = (4, 2, 1) over area 1/2: a Lambertian light of intensity 2 A L.
    CHECK(near(light.diffuseIntensity, {4, 2, 1}));
    CHECK(light.profile == rt::EmissionProfile::Lambertian);
    CHECK(scene.pointLights.empty());  // no framing light beside the model's own
    CHECK(scene.conventions == rt::Conventions::Physical);
    // An emissive texture makes a glow, not a light: its detail cannot be one light.
    const rt::Material& glowing = scene.materials.at(scene.shapes[2].material);
    CHECK(glowing.glow == glm::vec3(1.0f));
    CHECK_FALSE(glowing.glowTimesVertexColors);  // COLOR_0 multiplies base colours only
    REQUIRE(glowing.glowTexture >= 0);
    CHECK_FALSE(scene.textures.at(size_t(glowing.glowTexture)).linear);
    // Beside punctual lights (normalised to unit lights) a radiance has no
    // meaning: the shapes are drawn, but do not light.
    b.doc["extensionsUsed"].push_back("KHR_lights_punctual");
    b.doc["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "point"}}};
    b.node({{"translation", {0, 0, 4}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    scene = loadDoc("lit.gltf", b.embedded());
    CHECK(scene.areaLights.empty());
    CHECK(scene.pointLights.size() == 1);
    CHECK(scene.conventions == rt::Conventions::Textbook);
    CHECK(hasWarning(scene, "emission beside KHR_lights_punctual lights"));
  }

  TEST_CASE("base colour textures: decoded once, texCoord and KHR_texture_transform pick the uvs") {
    writeTexture("tex.png");
    GltfBuilder b;
    b.doc["extensionsUsed"] = {"KHR_texture_transform"};
    int pos = b.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    int uv0 = b.floats({1, 0, 0, 1, 1, 1}, "VEC2", 2);
    int uv1 = b.floats({0, 0, 1, 0, 0, 1}, "VEC2", 2);
    b.doc["images"] = {{{"uri", "tex.png"}}};
    b.doc["textures"] = {{{"source", 0}}};
    Json shifted = {
        {"index", 0},
        {"texCoord", 1},
        {"extensions", {{"KHR_texture_transform", {{"offset", {0.5, 0}}, {"scale", {2, 2}}}}}}};
    Json turned = {
        {"index", 0},
        {"extensions", {{"KHR_texture_transform", {{"rotation", glm::half_pi<double>()}}}}}};
    b.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", shifted}}}},
                          {{"pbrMetallicRoughness", {{"baseColorTexture", turned}}}}};
    Json attributes = {{"POSITION", pos}, {"TEXCOORD_0", uv0}, {"TEXCOORD_1", uv1}};
    b.node({{"mesh", b.mesh({{"attributes", attributes}, {"material", 0}})}});
    b.node({{"mesh", b.mesh({{"attributes", attributes}, {"material", 1}})}});
    rt::Scene scene = loadDoc("textured.gltf", b.embedded());
    REQUIRE(scene.textures.size() == 1);
    CHECK(scene.textures[0].image.width == 2);
    CHECK(scene.textures[0].image.rgba.size() == 16);
    CHECK(scene.textures[0].image.rgba[0] == 255);  // top-left red
    const rt::Material& material = scene.materials[scene.shapes[0].material];
    CHECK(material.diffuseTexture == 0);
    CHECK(material.texture.filename() == "tex.png");
    // The base colour factor (white by default) tints the texture.
    CHECK(material.textureTintedByColor);
    CHECK(material.diffuseColor == glm::vec3(1.0f));
    CHECK(scene.materials[scene.shapes[1].material].diffuseTexture == 0);
    CHECK(meshOf(scene, 0).uvs == std::vector<glm::vec2>{{0.5f, 0}, {2.5f, 0}, {0.5f, 2}});
    // Rotation by 90 degrees: u' = v, v' = -u.
    const std::vector<glm::vec2>& turnedUvs = meshOf(scene, 1).uvs;
    CHECK(glm::length(turnedUvs[0] - glm::vec2(0, -1)) < 1e-6f);
    CHECK(glm::length(turnedUvs[2] - glm::vec2(1, -1)) < 1e-6f);
  }

  TEST_CASE("transmission textures: data the kernels read where the base colour's are read") {
    writeTexture("tex.png");
    GltfBuilder b;
    int pos = b.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    int uv0 = b.floats({1, 0, 0, 1, 1, 1}, "VEC2", 2);
    b.doc["extensionsUsed"] = {"KHR_materials_transmission"};
    b.doc["images"] = {{{"uri", "tex.png"}}};
    b.doc["textures"] = {{{"source", 0}}};
    Json glass = {{"transmissionFactor", 0.5}, {"transmissionTexture", {{"index", 0}}}};
    Json elsewhere = {{"transmissionFactor", 1},
                      {"transmissionTexture", {{"index", 0}, {"texCoord", 1}}}};
    b.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
                           {"extensions", {{"KHR_materials_transmission", glass}}}},
                          {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
                           {"extensions", {{"KHR_materials_transmission", elsewhere}}}}};
    Json attributes = {{"POSITION", pos}, {"TEXCOORD_0", uv0}};
    b.node({{"mesh", b.mesh({{"attributes", attributes}, {"material", 0}})}});
    b.node({{"mesh", b.mesh({{"attributes", attributes}, {"material", 1}})}});
    rt::Scene scene = loadDoc("transmission.gltf", b.embedded());
    const rt::Material& textured = scene.materials[scene.shapes[0].material];
    CHECK(textured.transmission == 0.5f);
    REQUIRE(textured.transmissionTexture >= 0);
    CHECK(scene.textures.at(size_t(textured.transmissionTexture)).linear);
    // Other texture coordinates than the base colour's: not read, said so.
    CHECK(scene.materials[scene.shapes[1].material].transmissionTexture == -1);
    CHECK(hasWarning(scene, "reads other texture coordinates than the base colour texture"));
  }

  TEST_CASE("metallic-roughness textures: data, their factors, the mean's terms; tinted mirrors") {
    writeTexture("tex.png");  // 2 x 2: red, green, blue, white
    GltfBuilder b;
    int pos = b.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    int uv0 = b.floats({1, 0, 0, 1, 1, 1}, "VEC2", 2);
    b.doc["images"] = {{{"uri", "tex.png"}}};
    b.doc["textures"] = {{{"source", 0}}};
    b.doc["materials"] = {{{"pbrMetallicRoughness",
                            {{"baseColorTexture", {{"index", 0}}},
                             {"metallicRoughnessTexture", {{"index", 0}}},
                             {"metallicFactor", 0.5},
                             {"roughnessFactor", 0.8}}}},
                          {{"pbrMetallicRoughness",
                            {{"baseColorTexture", {{"index", 0}}},
                             {"metallicRoughnessTexture", {{"index", 0}, {"texCoord", 1}}}}}}};
    Json attributes = {{"POSITION", pos}, {"TEXCOORD_0", uv0}, {"TEXCOORD_1", uv0}};
    for (int material = 0; material < 2; ++material) {
      b.node({{"mesh", b.mesh({{"attributes", attributes}, {"material", material}})}});
    }
    rt::Scene scene = loadDoc("metal-rough.gltf", b.embedded());
    const rt::Material& textured = scene.materials[scene.shapes[0].material];
    REQUIRE(textured.metalRoughTexture >= 0);
    CHECK(scene.textures.at(size_t(textured.metalRoughTexture)).linear);
    CHECK(textured.metallic == 0.5f);
    CHECK(textured.roughness == 0.8f);
    CHECK(textured.tintedMirror);
    // Its own terms are the mean's: blue (metallic) and green (roughness) average 1/2.
    CHECK(textured.kd == doctest::Approx(1.0 - 0.25));
    CHECK(textured.reflectivity == doctest::Approx(0.25 * 0.6 * 0.6));
    const rt::Material& other = scene.materials[scene.shapes[1].material];
    CHECK(other.metalRoughTexture == -1);
    CHECK(hasWarning(scene,
                     "materials[1].pbrMetallicRoughness.metallicRoughnessTexture: reads other "
                     "texture coordinates than the base colour texture; ignored"));
  }

  TEST_CASE("alpha modes: MASK's cutoff, BLEND, the base colour's alpha; unknown modes opaque") {
    Json textured = {{"baseColorTexture", {{"index", 0}}}, {"baseColorFactor", {1, 1, 1, 0.75}}};
    GltfBuilder b = texturedTriangles(
        {{{"alphaMode", "MASK"}, {"alphaCutoff", 0.25}, {"pbrMetallicRoughness", textured}},
         {{"alphaMode", "BLEND"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 0, 0, 0.5}}}}},
         {{"alphaMode", "MASK"}},
         {{"alphaMode", "OPAQUE"}, {"pbrMetallicRoughness", textured}},
         {{"alphaMode", "CUTOUT"}},
         {{"alphaMode", "MASK"}, {"alphaCutoff", -1}}});
    rt::Scene scene = loadDoc("alpha.gltf", b.embedded());
    auto materialOf = [&](size_t shape) { return scene.materials[scene.shapes[shape].material]; };
    using Alpha = rt::Material::Alpha;
    CHECK(materialOf(0).alphaMode == Alpha::Mask);
    CHECK(materialOf(0).alphaCutoff == 0.25f);
    CHECK(materialOf(0).alphaFactor == 0.75f);
    CHECK(materialOf(0).alphaTexture == materialOf(0).diffuseTexture);
    CHECK(materialOf(0).alphaTexture >= 0);
    CHECK(materialOf(1).alphaMode == Alpha::Blend);
    CHECK(materialOf(1).alphaFactor == 0.5f);
    CHECK(materialOf(1).alphaTexture == -1);
    CHECK(materialOf(2).alphaCutoff == 0.5f);  // glTF's default
    CHECK(materialOf(2).alphaFactor == 1.0f);
    // OPAQUE: alpha means nothing, the texture is only colour.
    CHECK(materialOf(3).alphaMode == Alpha::Opaque);
    CHECK(materialOf(3).alphaTexture == -1);
    CHECK(materialOf(4).alphaMode == Alpha::Opaque);
    CHECK(hasWarning(scene,
                     "materials[4].alphaMode: unknown mode \"CUTOUT\" (OPAQUE, MASK or "
                     "BLEND); drawn opaque"));
    CHECK(materialOf(5).alphaCutoff == 0.0f);
    CHECK(hasWarning(scene, "materials[5].alphaCutoff: negative; taken as 0"));
    CHECK_FALSE(hasWarning(scene, "alpha modes"));
  }

  TEST_CASE(
      "KHR_materials_unlit: the base colour as a glow, factor times texture and vertex colours; no "
      "lights") {
    Json unlit = {{"KHR_materials_unlit", Json::object()}};
    GltfBuilder b = texturedTriangles(
        {{{"extensions", unlit},
          {"emissiveFactor", {1, 1, 1}},
          {"pbrMetallicRoughness",
           {{"baseColorTexture", {{"index", 0}}}, {"baseColorFactor", {0.5, 1, 1, 1}}}}},
         {{"extensions", unlit}, {"pbrMetallicRoughness", {{"baseColorFactor", {0, 1, 0, 1}}}}}});
    b.doc["extensionsUsed"] = {"KHR_materials_unlit"};
    rt::Scene scene = loadDoc("unlit.gltf", b.embedded());
    const rt::Material& textured = scene.materials[scene.shapes[0].material];
    CHECK(textured.glow == glm::vec3(0.5f, 1, 1));
    CHECK(textured.glowTexture == textured.diffuseTexture);
    CHECK(textured.glowTexture >= 0);
    CHECK(textured.glowTimesVertexColors);
    CHECK(textured.kd == 0.0f);
    CHECK(textured.ks == 0.0f);
    CHECK(textured.reflectivity == 0.0f);
    const rt::Material& plain = scene.materials[scene.shapes[1].material];
    CHECK(plain.glow == glm::vec3(0, 1, 0));
    CHECK(plain.glowTexture == -1);
    // Its emissive factor is not read: no area light; no warning for the extension.
    CHECK(scene.areaLights.empty());
    CHECK_FALSE(hasWarning(scene, "KHR_materials_unlit"));
  }

  TEST_CASE("samplers: wrap modes and the magnification filter; one image, two samplers") {
    GltfBuilder b =
        texturedTriangles({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}},
                           {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 1}}}}}},
                           {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 2}}}}}}});
    b.doc["samplers"] = {{{"wrapS", 33071}, {"wrapT", 33648}, {"magFilter", 9728}},
                         {{"wrapS", 12345}}};
    b.doc["textures"] = {
        {{"source", 0}, {"sampler", 0}}, {{"source", 0}}, {{"source", 0}, {"sampler", 1}}};
    rt::Scene scene = loadDoc("samplers.gltf", b.embedded());
    auto samplingOf = [&](size_t shape) {
      const rt::Material& material = scene.materials[scene.shapes[shape].material];
      return scene.textures.at(size_t(material.diffuseTexture)).sampling;
    };
    using Wrap = rt::TextureSampling::Wrap;
    CHECK(samplingOf(0).wrapU == Wrap::Clamp);
    CHECK(samplingOf(0).wrapV == Wrap::Mirror);
    CHECK(samplingOf(0).nearest);
    CHECK(samplingOf(1).isDefault());  // no sampler: repeat, bilinear
    CHECK(samplingOf(2).isDefault());  // an unknown mode repeats
    CHECK(hasWarning(scene, "samplers[1].wrapS: unknown wrap mode 12345; repeats"));
    // The image once per sampling: the first two textures apart, the last two shared.
    CHECK(scene.textures.size() == 2);
    b.doc["textures"][0]["sampler"] = 5;
    CHECK(contains(errorOfDoc("bad-sampler.gltf", b.embedded()),
                   "sampler 5 does not exist (the file has 2)"));
  }

  TEST_CASE("normal maps: decoded as data beside the same image as colour, scale, one uv set") {
    writeTexture("tex.png");
    GltfBuilder b;
    int pos = b.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    int uv0 = b.floats({1, 0, 0, 1, 1, 1}, "VEC2", 2);
    int uv1 = b.floats({0, 0, 1, 0, 0, 1}, "VEC2", 2);
    b.doc["images"] = {{{"uri", "tex.png"}}};
    b.doc["textures"] = {{{"source", 0}}};
    b.doc["materials"] = {
        {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
         {"normalTexture", {{"index", 0}, {"scale", 0.5}}}},
        {{"normalTexture", {{"index", 0}, {"texCoord", 1}}}},  // alone: its uvs are the mesh's
        {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
         {"normalTexture", {{"index", 0}, {"texCoord", 1}}}}};  // two uv sets: not drawn
    Json attributes = {{"POSITION", pos}, {"TEXCOORD_0", uv0}, {"TEXCOORD_1", uv1}};
    for (int material = 0; material < 3; ++material) {
      b.node({{"mesh", b.mesh({{"attributes", attributes}, {"material", material}})}});
    }
    rt::Scene scene = loadDoc("normals.gltf", b.embedded());
    // One image, twice: as sRGB colours and as linear data.
    REQUIRE(scene.textures.size() == 2);
    const rt::Material& both = scene.materials[scene.shapes[0].material];
    CHECK_FALSE(scene.textures.at(size_t(both.diffuseTexture)).linear);
    REQUIRE(both.normalTexture >= 0);
    CHECK(scene.textures.at(size_t(both.normalTexture)).linear);
    CHECK(both.normalScale == 0.5f);
    const rt::Material& alone = scene.materials[scene.shapes[1].material];
    CHECK(alone.normalTexture == both.normalTexture);
    CHECK(alone.normalScale == 1.0f);
    CHECK(meshOf(scene, 1).uvs == std::vector<glm::vec2>{{0, 0}, {1, 0}, {0, 1}});  // TEXCOORD_1
    CHECK(scene.materials[scene.shapes[2].material].normalTexture == -1);
    CHECK(hasWarning(scene,
                     "materials[2].normalTexture: reads other texture coordinates than the "
                     "base colour texture; ignored"));
  }

  TEST_CASE("cameras: the first perspective camera of the scene, its node's axes and aspect") {
    GltfBuilder b = triangleModel();
    b.doc["cameras"] = {
        {{"type", "orthographic"},
         {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 10}}}},
        {{"type", "perspective"},
         {"perspective", {{"yfov", 0.5}, {"aspectRatio", 1.5}, {"znear", 0.1}}}},
        {{"type", "perspective"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.1}}}}};
    double h = std::sqrt(0.5);  // 90 degrees about y: -z becomes -x
    b.node({{"camera", 0}});
    b.node({{"camera", 1}, {"translation", {5, 1, 0}}, {"rotation", {0, h, 0, h}}});
    b.node({{"camera", 2}});
    rt::Scene scene = loadDoc("cameras.gltf", b.embedded());
    CHECK(scene.camera.fovYDegrees == doctest::Approx(glm::degrees(0.5)));
    CHECK(scene.camera.width == 900);
    CHECK(scene.camera.height == 600);
    CHECK(near(scene.camera.position, {5, 1, 0}));
    CHECK(near(scene.camera.forward, {-1, 0, 0}));
    CHECK(near(scene.camera.up, {0, 1, 0}));
    CHECK(hasWarning(scene, "orthographic cameras ignored (cameras[0])"));
    CHECK(hasWarning(scene, "cameras after the first ignored (cameras[2])"));
  }

  TEST_CASE("the default scene decides what is drawn; without scenes every root node") {
    GltfBuilder b = triangleModel();
    b.node({{"mesh", 0}, {"translation", {0, 0, 7}}}, false);
    b.doc["scenes"].push_back({{"nodes", {1}}});
    b.doc["scene"] = 1;
    rt::Scene second = loadDoc("scene1.gltf", b.embedded());
    REQUIRE(second.shapes.size() == 1);
    CHECK(instanceOf(second, 0).objectToWorld[3].z == 7.0f);
    b.doc.erase("scene");
    CHECK(instanceOf(loadDoc("scene0.gltf", b.embedded()), 0).objectToWorld[3].z == 0.0f);
    b.doc.erase("scenes");
    rt::Scene all = loadDoc("noscene.gltf", b.embedded());
    CHECK(all.shapes.size() == 2);
    CHECK(hasWarning(all, "the file has no scene"));
  }

  TEST_CASE("appendGltf places the model, shifts indices, and changes nothing when it fails") {
    writeTexture("tex.png");
    GltfBuilder b = triangleModel();
    b.doc["images"] = {{{"uri", "tex.png"}}};
    b.doc["textures"] = {{{"source", 0}}};
    b.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    fs::path file = writeGltf("append.gltf", b.embedded());
    rt::Scene scene;
    scene.camera.position = {1, 2, 3};
    scene.materials.push_back({});
    scene.textures.push_back({"other.png", {1, 1, {0, 0, 0, 255}}});
    scene.meshes.push_back({});
    scene.shapes.push_back({rt::MeshInstance{0, rt::WorldTransform(1.0)}, 0, "first"});
    rt::appendGltf(scene, file, glm::translate(rt::WorldTransform(1.0), glm::dvec3(10, 0, 0)));
    REQUIRE(scene.shapes.size() == 2);
    CHECK(instanceOf(scene, 1).mesh == 1);
    CHECK(scene.shapes[1].material == 1);
    CHECK(scene.materials[1].diffuseTexture == 1);
    CHECK(scene.textures.size() == 2);
    CHECK(near(place(instanceOf(scene, 1).objectToWorld, {1, 0, 0}), {11, 0, 0}));
    CHECK(scene.camera.position == rt::WorldPoint(1, 2, 3));
    CHECK(scene.conventions == rt::Conventions::CourseworkA);
    CHECK(scene.pointLights.empty());  // no default light when appending

    b.doc["meshes"][0]["primitives"][0]["indices"] = 7;
    fs::path broken = writeGltf("append-broken.gltf", b.embedded());
    CHECK_THROWS_AS(rt::appendGltf(scene, broken, rt::WorldTransform(1.0)), rt::Error);
    CHECK(scene.shapes.size() == 2);
    CHECK(scene.materials.size() == 2);
    CHECK(scene.meshes.size() == 2);
    CHECK(scene.textures.size() == 2);
  }

  TEST_CASE("unusable normals and unknown optional extensions are warnings, not errors") {
    GltfBuilder b;
    b.doc["extensionsUsed"] = {"EXT_something_new"};
    int pos = b.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    int nrm = b.floats({0, 0, 1, 0, 0, 0, 0, 0, 1}, "VEC3", 3);
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}})}});
    rt::Scene scene = loadDoc("bad-normals.gltf", b.embedded());
    CHECK(scene.meshes.at(0).normals.empty());
    CHECK(hasWarning(scene, "attributes.NORMAL: 1 normals are zero or not finite"));
    CHECK(hasWarning(scene, "uses extension EXT_something_new, which is ignored"));
  }
}

TEST_SUITE("scene gltf errors") {
  TEST_CASE("node hierarchies must be trees") {
    GltfBuilder b = triangleModel();
    b.node({{"children", {1}}}, false);
    CHECK(contains(errorOfDoc("self.gltf", b.embedded()), "nodes[1]: is its own ancestor"));
    b.doc["nodes"][1]["children"] = {2};
    b.node({{"children", {1}}}, false);
    CHECK(contains(errorOfDoc("cycle.gltf", b.embedded()), "is its own ancestor"));
    b.doc["nodes"][2]["children"] = {0};
    b.doc["nodes"][1]["children"] = {0};
    CHECK(contains(errorOfDoc("two-parents.gltf", b.embedded()),
                   "nodes[2].children[0]: node 0 is already a child of nodes[1]"));
    b.doc["nodes"][2]["children"] = Json::array();
    CHECK(contains(errorOfDoc("child-root.gltf", b.embedded()),
                   "scenes[0].nodes[0]: node 0 is not a root node (it is a child of nodes[1])"));
    b.doc["nodes"][1]["children"] = {9};
    CHECK(contains(errorOfDoc("no-child.gltf", b.embedded()),
                   "nodes[1].children[0]: node 9 does not exist"));
  }

  TEST_CASE("accessors and buffer views are checked against the real buffer sizes") {
    auto withAccessor = [](const char* key, Json value) {
      GltfBuilder b = triangleModel();
      b.doc["accessors"][0][key] = value;
      return b.embedded();
    };
    std::string where = "meshes[0].primitives[0].attributes.POSITION: accessor 0";
    CHECK(contains(errorOfDoc("count.gltf", withAccessor("count", 4)),
                   where + " reads past the end of buffer view 0"));
    CHECK(contains(errorOfDoc("huge-count.gltf", withAccessor("count", uint64_t(4000000000))),
                   where + " reads past the end of buffer view 0"));
    CHECK(contains(errorOfDoc("offset.gltf", withAccessor("byteOffset", 8)),
                   where + " reads past the end of buffer view 0"));
    CHECK(contains(errorOfDoc("type.gltf", withAccessor("type", "VEC2")),
                   where + ": type VEC2 where VEC3 is required"));
    CHECK(contains(errorOfDoc("zero.gltf", withAccessor("count", 0)), where + " has count 0"));
    GltfBuilder b = triangleModel();
    b.doc["bufferViews"][0]["byteLength"] = 1000;
    CHECK(contains(errorOfDoc("view.gltf", b.embedded()),
                   "buffer view 0 (bytes 0 + 1000) lies outside buffer 0 (42 bytes)"));
    b = triangleModel();
    b.doc["bufferViews"][0]["byteStride"] = 4;
    CHECK(contains(errorOfDoc("stride.gltf", b.embedded()),
                   "byteStride 4 of buffer view 0 is smaller than one element (12 bytes)"));
    b = triangleModel();
    b.doc["accessors"][0].erase("bufferView");
    CHECK(contains(errorOfDoc("no-view.gltf", b.embedded()),
                   "has neither a buffer view nor sparse values"));
  }

  TEST_CASE("indices, attributes, modes and materials are checked") {
    GltfBuilder b = triangleModel();
    b.bin[36 + 4] = 3;  // the third index: 2 -> 3
    CHECK(contains(
        errorOfDoc("index.gltf", b.embedded()),
        "meshes[0].primitives[0].indices: index 2 is 3, but POSITION has only 3 vertices"));
    b = triangleModel();
    b.doc["accessors"][1]["componentType"] = 5126;
    CHECK(contains(errorOfDoc("float-indices.gltf", b.embedded()),
                   "indices: accessor 1: componentType FLOAT is not allowed here"));
    b = triangleModel();
    b.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] =
        b.floats({0, 0, 1, 0, 0, 1}, "VEC3", 3);
    CHECK(contains(errorOfDoc("normal-count.gltf", b.embedded()),
                   "attributes.NORMAL: accessor 2 has 2 elements, POSITION has 3"));
    b = triangleModel();
    b.doc["meshes"][0]["primitives"][0]["mode"] = 9;
    CHECK(contains(errorOfDoc("mode.gltf", b.embedded()),
                   "meshes[0].primitives[0].mode: 9 is not a glTF primitive mode"));
    b = triangleModel();
    b.doc["meshes"][0]["primitives"][0]["material"] = 7;
    CHECK(contains(errorOfDoc("material.gltf", b.embedded()),
                   "meshes[0].primitives[0].material: material 7 does not exist"));
    b = triangleModel();
    b.doc["meshes"][0]["primitives"][0]["attributes"].erase("POSITION");
    b.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 0;
    CHECK(contains(errorOfDoc("no-position.gltf", b.embedded()), "POSITION is missing"));
    b = triangleModel();
    b.doc["nodes"][0]["mesh"] = 3;
    CHECK(contains(errorOfDoc("mesh.gltf", b.embedded()), "nodes[0].mesh: mesh 3 does not exist"));
  }

  TEST_CASE("transforms must be finite and affine") {
    GltfBuilder b = triangleModel();
    b.doc["nodes"][0]["matrix"] = {7777, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    std::string text = b.embedded().dump();
    text.replace(text.find("7777"), 4, "1e999");
    // JSON has no infinity: numbers beyond double are a parse error.
    CHECK(contains(errorOf(writeBytes("inf.gltf", text)), "number overflow parsing '1e999'"));
    b.doc["nodes"][0]["matrix"] = {1, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    CHECK(contains(errorOfDoc("projective.gltf", b.embedded()),
                   "nodes[0].matrix: is not an affine transform"));
    b.doc["nodes"][0].erase("matrix");
    b.doc["nodes"][0]["rotation"] = {0, 0, 0, 0};
    CHECK(contains(errorOfDoc("quaternion.gltf", b.embedded()),
                   "nodes[0].rotation: is a zero quaternion"));
    b.doc["nodes"][0]["rotation"] = {0, 0, 1};
    CHECK(contains(errorOfDoc("rotation.gltf", b.embedded()),
                   "nodes[0].rotation: has 3 numbers, 4 are required"));
    b = triangleModel();
    b.doc["nodes"][0]["scale"] = {1e300, 1, 1};
    b.node({{"children", {0}}, {"scale", {1e300, 1, 1}}});
    b.doc["scenes"][0]["nodes"] = {1};
    CHECK(contains(errorOfDoc("overflow.gltf", b.embedded()),
                   "nodes[0]: its world transform overflows"));
    b = triangleModel();
    b.doc["nodes"][0]["scale"] = {1, 0, 1};
    rt::Scene flat = loadDoc("zero-scale.gltf", b.embedded());
    CHECK(flat.shapes.empty());
    CHECK(hasWarning(flat, "nodes with a zero scale (not drawn) ignored (nodes[0])"));
  }

  TEST_CASE("versions, required extensions, scenes, cameras and lights") {
    GltfBuilder b = triangleModel();
    b.doc["extensionsRequired"] = {"KHR_materials_transmission", "EXT_unknown"};
    CHECK(contains(errorOfDoc("required.gltf", b.embedded()),
                   ": glTF requires extension EXT_unknown, which is not supported"));
    b = triangleModel();
    b.doc["asset"]["version"] = "1.0";
    CHECK(contains(errorOfDoc("version.gltf", b.embedded()),
                   "asset.version: glTF '1.0' is not supported"));
    b = triangleModel();
    b.doc["scene"] = 5;
    CHECK(contains(errorOfDoc("scene.gltf", b.embedded()),
                   ": scene: scene 5 does not exist (the file has 1)"));
    b = triangleModel();
    b.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 4}, {"znear", 0.1}}}}};
    b.doc["nodes"][0]["camera"] = 0;
    CHECK(contains(errorOfDoc("yfov.gltf", b.embedded()),
                   "cameras[0].perspective.yfov: must be between 0 and pi radians"));
    b = triangleModel();
    b.doc["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "point"}}};
    b.doc["nodes"][0]["extensions"]["KHR_lights_punctual"]["light"] = 3;
    CHECK(contains(errorOfDoc("light.gltf", b.embedded()),
                   "nodes[0].extensions.KHR_lights_punctual.light: light 3 does not exist"));
  }

  TEST_CASE("files: missing, empty, not glTF, missing buffer or image, broken GLB framing") {
    fs::path missing = scratchDir() / "does-not-exist.gltf";
    CHECK(contains(errorOf(missing), "cannot open"));
    CHECK(!errorOf(writeBytes("empty.gltf", "")).empty());
    CHECK(!errorOf(writeBytes("text.gltf", "hello")).empty());
    CHECK(!errorOf(writeBytes("array.gltf", "[1, 2, 3]")).empty());
    GltfBuilder b = triangleModel();
    Json doc = b.embedded();
    doc["buffers"][0]["uri"] = "missing.bin";
    CHECK(contains(errorOfDoc("missing-bin.gltf", doc), "buffers[0]: cannot read 'missing.bin'"));
    doc["buffers"][0]["uri"] = "/dev/zero";
    CHECK(!errorOfDoc("dev-zero.gltf", doc).empty());
    b.doc["images"] = {{{"uri", "missing.png"}}};
    b.doc["textures"] = {{{"source", 0}}};
    b.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    CHECK(contains(errorOfDoc("missing-png.gltf", b.embedded()),
                   "materials[0].pbrMetallicRoughness.baseColorTexture: images[0]: "));
    // A FIFO would block a reader forever: only regular files are read.
    fs::path fifo = scratchDir() / "fifo.png";
    fs::remove(fifo);
    REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
    b.doc["images"][0]["uri"] = "fifo.png";
    CHECK(contains(errorOfDoc("fifo-png.gltf", b.embedded()), "not a regular file"));
    doc["buffers"][0]["uri"] = "fifo.png";
    CHECK(contains(errorOfDoc("fifo-bin.gltf", doc),
                   "buffers[0]: cannot read 'fifo.png': not a regular file"));

    GltfBuilder images = triangleModel();
    int view = images.view(std::vector<uint8_t>{1, 2, 3, 4});
    images.doc["bufferViews"][view]["byteOffset"] = 100000;
    images.doc["images"] = {{{"bufferView", view}, {"mimeType", "image/png"}}};
    CHECK(contains(errorOf(writeBytes("image-view.glb", glbBytes(images))),
                   "images[0]: buffer view 2 (bytes 100000 + 4) lies outside buffer 0"));

    std::string glb = glbBytes(triangleModel());
    CHECK(contains(errorOf(writeBytes("short.glb", glb.substr(0, glb.size() - 8))),
                   "GLB: truncated"));
    std::string version = glb;
    version[4] = 1;
    CHECK(contains(errorOf(writeBytes("v1.glb", version)), "GLB: version 1 is not supported"));
    std::string chunk = glb;
    chunk[13] = char(0x7F);  // JSON chunk length beyond the file
    CHECK(contains(errorOf(writeBytes("chunk.glb", chunk)), "run past the end of the file"));
    std::string notJson = glb;
    notJson[16] = 'X';
    CHECK(contains(errorOf(writeBytes("type.glb", notJson)), "GLB: the first chunk is not JSON"));
  }

  TEST_CASE("hostile sizes: deep nesting, absurd object counts, data reused absurdly often") {
    GltfBuilder b = triangleModel();
    std::string text = b.embedded().dump();
    std::string deep = std::string(5000, '[') + std::string(5000, ']');
    text.insert(text.size() - 1, ",\"extras\":" + deep);
    CHECK(contains(errorOf(writeBytes("deep.gltf", text)), "JSON nests deeper than 100 levels"));

    std::string many = "{\"asset\":{\"version\":\"2.0\"},\"nodes\":[";
    for (int i = 0; i < 4'000'000; ++i) many += "{},";
    many += "{}]}";
    auto start = std::chrono::steady_clock::now();
    CHECK(contains(errorOf(writeBytes("many.gltf", many)), "MiB to parse"));
    CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(5));

    // 60 000 vertices read 300 times: far more memory than the buffer justifies.
    GltfBuilder reuse;
    std::vector<float> xyz(180000);
    for (size_t i = 0; i < xyz.size(); ++i) xyz[i] = float(i % 7);
    int pos = reuse.positions(xyz);
    Json primitive = {{"attributes", {{"POSITION", pos}}}};
    reuse.doc["meshes"] = {{{"primitives", Json::array()}}};
    for (int i = 0; i < 300; ++i) reuse.doc["meshes"][0]["primitives"].push_back(primitive);
    reuse.node({{"mesh", 0}});
    CHECK(contains(errorOfDoc("reuse.gltf", reuse.embedded()),
                   "the model needs more memory than its buffers justify"));
  }

  TEST_CASE("every corrupted variant of a small glTF loads soundly or fails with rt::Error") {
    // A document with a bit of everything, each value replaced or removed in turn.
    writeTexture("tex.png");
    GltfBuilder b = triangleModel();
    int nrm = b.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
    int uv = b.floats({0, 0, 1, 0, 0, 1}, "VEC2", 2);
    b.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = nrm;
    b.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = uv;
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    b.doc["images"] = {{{"uri", "tex.png"}}};
    b.doc["textures"] = {{{"source", 0}}};
    b.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    b.doc["cameras"] = {
        {{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.1}}}}};
    b.doc["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "directional"}}};
    b.node({{"camera", 0},
            {"translation", {0, 0, 3}},
            {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}},
            {"children", {2}}});
    b.node({{"mesh", 0}, {"scale", {-1, 2, 1}}}, false);
    Json document = b.embedded();
    const std::vector<Json> replacements = {nullptr,        "text",   -1,  0,    2,
                                            4000000000.0,   1e30,     0.5, true, Json::array(),
                                            Json::object(), {1, 2, 3}};
    size_t loaded = 0, rejected = 0;
    rt::test::forEachMutation<Json>(
        document, replacements, [&](const Json::json_pointer& pointer, const Json& variant) {
          try {
            rt::Scene scene = loadDoc("corrupt.gltf", variant);
            std::string problem = unsoundness(scene);
            CHECK_MESSAGE(problem.empty(), pointer.to_string() << ": " << problem);
            ++loaded;
          } catch (const rt::Error& error) {
            CHECK_MESSAGE(!contains(error.what(), "\n"), error.what());
            ++rejected;
          } catch (const std::exception& error) {
            FAIL("not an rt::Error at " << pointer.to_string() << ": " << error.what());
          }
        });
    MESSAGE(loaded << " variants loaded, " << rejected << " rejected");
  }
}

TEST_SUITE("scene gltf samples" * rt::test::needsShared()) {
  TEST_CASE("survey: every Khronos sample file loads soundly, Draco variants too") {
    const fs::path dir = assetDir("gltf/khronos-sample-assets");
    size_t files = 0, draco = 0;
    for (const fs::path& file : gltfFilesUnder(dir)) {
      std::string relative = fs::relative(file, dir).string();
      ++files;
      if (contains(relative, "glTF-Draco")) ++draco;
      try {
        rt::Scene scene = rt::loadGltfScene(file);
        MESSAGE(relative << ": " << summary(scene));
        CHECK_MESSAGE(drawnTriangles(scene) > 0, relative);
        CHECK_MESSAGE(unsoundness(scene).empty(), relative << ": " << unsoundness(scene));
      } catch (const rt::Error& error) {
        FAIL_CHECK(relative << ": rejected: " << error.what());
      }
    }
    CHECK(files > 50);
    CHECK(draco == 3);
  }

  TEST_CASE("Draco variants: the meshes of their uncompressed twins, up to quantization") {
    for (const char* name : {"Box", "Duck", "CesiumMilkTruck"}) {
      CAPTURE(name);
      const std::string model(name);
      rt::Scene plain = rt::loadGltfScene(sample((model + "/glTF/" + model + ".gltf").c_str()));
      rt::Scene draco =
          rt::loadGltfScene(sample((model + "/glTF-Draco/" + model + ".gltf").c_str()));
      REQUIRE(draco.meshes.size() == plain.meshes.size());
      for (size_t i = 0; i < plain.meshes.size(); ++i) {
        CHECK(draco.meshes[i].faces.size() == plain.meshes[i].faces.size());
        CHECK(draco.meshes[i].normals.empty() == plain.meshes[i].normals.empty());
        CHECK(draco.meshes[i].uvs.empty() == plain.meshes[i].uvs.empty());
      }
      // Draco's quantization moves vertices by a small part of the model's size.
      Box3 a = worldBounds(plain), b = worldBounds(draco);
      float size = glm::length(a.hi - a.lo);
      CHECK(near(a.lo, b.lo, 0.01f * size));
      CHECK(near(a.hi, b.hi, 0.01f * size));
    }
  }

  TEST_CASE(
      "Box: .gltf, .glb and embedded variants give identical meshes, placed by the node matrix") {
    const fs::path gltf = sample("Box/glTF/Box.gltf");
    rt::Scene scene = rt::loadGltfScene(gltf);
    CHECK(sameMeshes(scene, rt::loadGltfScene(sample("Box/glTF-Binary/Box.glb"))));
    CHECK(sameMeshes(scene, rt::loadGltfScene(sample("Box/glTF-Embedded/Box.gltf"))));
    REQUIRE(scene.meshes.size() == 1);
    CHECK(scene.meshes[0].faces.size() == 12);
    CHECK(scene.meshes[0].positions.size() == 24);
    CHECK(scene.meshes[0].normals.size() == 24);
    // The root node turns z-up into y-up: the unit cube stays a unit cube.
    Box3 box = worldBounds(scene);
    CHECK(near(box.lo, glm::vec3(-0.5f)));
    CHECK(near(box.hi, glm::vec3(0.5f)));
    CHECK(near(scene.materials.at(0).diffuseColor, {0.8f, 0, 0}));
    CHECK(scene.materials.at(0).kd == doctest::Approx(1.0));
    // Interleaved attributes (byte strides) give the same world-space box.
    rt::Scene interleaved = rt::loadGltfScene(sample("BoxInterleaved/glTF/BoxInterleaved.gltf"));
    CHECK(uniqueTriangles(interleaved) == 12);
    CHECK(near(worldBounds(interleaved).lo, box.lo));
    CHECK(near(worldBounds(interleaved).hi, box.hi));
  }

  TEST_CASE("Triangle, TriangleWithoutIndices, SimpleSparseAccessor, MeshPrimitiveModes") {
    const fs::path triangle = sample("Triangle/glTF/Triangle.gltf");
    rt::Scene indexed = rt::loadGltfScene(triangle);
    rt::Scene plain =
        rt::loadGltfScene(sample("TriangleWithoutIndices/glTF/TriangleWithoutIndices.gltf"));
    CHECK(indexed.meshes.at(0).positions == plain.meshes.at(0).positions);
    CHECK(indexed.meshes.at(0).faces == plain.meshes.at(0).faces);
    // Sparse values lift three vertices: the accessor's max becomes (6, 4, 0).
    rt::Scene sparse =
        rt::loadGltfScene(sample("SimpleSparseAccessor/glTF/SimpleSparseAccessor.gltf"));
    CHECK(near(worldBounds(sparse).hi, {6, 4, 0}));
    CHECK(near(worldBounds(sparse).lo, {0, 0, 0}));
    CHECK(uniqueTriangles(sparse) == 12);
    // Triangles 6, strip 4, fan 6; points and three kinds of lines skipped.
    rt::Scene modes = rt::loadGltfScene(sample("MeshPrimitiveModes/glTF/MeshPrimitiveModes.gltf"));
    REQUIRE(modes.meshes.size() == 3);
    CHECK(modes.meshes[0].faces.size() == 6);
    CHECK(modes.meshes[1].faces.size() == 4);
    CHECK(modes.meshes[2].faces.size() == 6);
    CHECK(hasWarning(modes,
                     "points and lines (primitive modes 0 to 3) ignored (meshes[0].primitives[0], "
                     "meshes[1].primitives[0], meshes[2].primitives[0], meshes[3].primitives[0])"));
  }

  TEST_CASE("instancing: SimpleMeshes, CesiumMilkTruck, SimpleInstancing share their meshes") {
    const fs::path meshes = sample("SimpleMeshes/glTF/SimpleMeshes.gltf");
    rt::Scene twice = rt::loadGltfScene(meshes);
    CHECK(twice.meshes.size() == 1);
    CHECK(twice.shapes.size() == 2);
    rt::Scene truck = rt::loadGltfScene(sample("CesiumMilkTruck/glTF/CesiumMilkTruck.gltf"));
    CHECK(truck.meshes.size() == 4);  // the wheels' mesh serves two nodes
    CHECK(truck.shapes.size() == 5);
    CHECK(drawnTriangles(truck) > uniqueTriangles(truck));
    rt::Scene cubes = rt::loadGltfScene(sample("SimpleInstancing/glTF/SimpleInstancing.gltf"));
    CHECK(cubes.meshes.size() == 1);
    CHECK(cubes.shapes.size() == 125);
    CHECK(drawnTriangles(cubes) == 125 * 12);
  }

  TEST_CASE("NegativeScaleTest: mirrored instances keep winding and normals in agreement") {
    const fs::path file = sample("NegativeScaleTest/glTF/NegativeScaleTest.gltf");
    rt::Scene scene = rt::loadGltfScene(file);
    CHECK(scene.meshes.size() == 11);  // 8 glTF meshes, 3 used mirrored and not
    size_t mirrored = 0;
    for (size_t shape = 0; shape < scene.shapes.size(); ++shape) {
      const rt::TriangleMesh& mesh = meshOf(scene, shape);
      if (mesh.normals.empty()) continue;
      glm::mat4 m(instanceOf(scene, shape).objectToWorld);
      if (glm::determinant(glm::mat3(m)) < 0.0f) ++mirrored;
      glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(m)));
      size_t agree = 0;
      for (size_t f = 0; f < mesh.faces.size(); ++f) {
        glm::uvec3 face = mesh.faces[f];
        glm::vec3 n =
            normalMatrix * (mesh.normals[face.x] + mesh.normals[face.y] + mesh.normals[face.z]);
        if (glm::dot(windingNormal(scene, shape, f), n) > 0.0f) ++agree;
      }
      CHECK_MESSAGE(agree > mesh.faces.size() * 9 / 10, scene.shapes[shape].label);
    }
    CHECK(mirrored >= 4);
  }

  TEST_CASE("Cameras, MultipleScenes, TransmissionTest, BoxTextured, Duck quantized") {
    const fs::path cameras = sample("Cameras/glTF/Cameras.gltf");
    rt::Scene withCamera = rt::loadGltfScene(cameras);
    CHECK(withCamera.camera.fovYDegrees == doctest::Approx(glm::degrees(0.7)));
    CHECK(withCamera.camera.width == 600);
    CHECK(near(withCamera.camera.position, {0.5f, 0.5f, 3.0f}));
    CHECK(near(withCamera.camera.forward, {0, 0, -1}));
    // "scene": 1 holds the square (two triangles), scene 0 the triangle.
    rt::Scene second = rt::loadGltfScene(sample("MultipleScenes/glTF/MultipleScenes.gltf"));
    CHECK(uniqueTriangles(second) == 2);
    rt::Scene glass = rt::loadGltfScene(sample("TransmissionTest/glTF/TransmissionTest.gltf"));
    CHECK(std::any_of(glass.materials.begin(), glass.materials.end(), [](const rt::Material& m) {
      return m.transmission == 1.0f && m.ior == 1.5f && m.kd == 0.0f;
    }));
    rt::Scene textured = rt::loadGltfScene(sample("BoxTextured/glTF/BoxTextured.gltf"));
    REQUIRE(textured.textures.size() == 1);
    CHECK(textured.textures[0].image.width == 256);
    CHECK(textured.materials.at(0).diffuseTexture == 0);
    CHECK(textured.meshes.at(0).uvs.size() == 24);
    // TextureCoordinateTest colours one texture with four base colour factors.
    rt::Scene tinted =
        rt::loadGltfScene(sample("TextureCoordinateTest/glTF/TextureCoordinateTest.gltf"));
    int tintedTextures = 0;
    for (const rt::Material& m : tinted.materials) {
      if (m.diffuseTexture < 0) continue;
      ++tintedTextures;
      CHECK(m.textureTintedByColor);
      CHECK(m.diffuseColor != glm::vec3(1.0f));
    }
    CHECK(tintedTextures == 4);
    rt::Scene glb = rt::loadGltfScene(sample("BoxTextured/glTF-Binary/BoxTextured.glb"));
    CHECK(glb.textures.at(0).image.rgba == textured.textures[0].image.rgba);
    rt::Scene duck = rt::loadGltfScene(sample("Duck/glTF/Duck.gltf"));
    rt::Scene quantized = rt::loadGltfScene(sample("Duck/glTF-Quantized/Duck.gltf"));
    CHECK(uniqueTriangles(duck) == 4212);
    CHECK(uniqueTriangles(quantized) == 4212);
    CHECK(near(worldBounds(duck).lo, worldBounds(quantized).lo, 0.05f));
    CHECK(near(worldBounds(duck).hi, worldBounds(quantized).hi, 0.05f));
    // DamagedHelmet's metal and roughness come from a texture: its mean is used.
    rt::Scene helmet = rt::loadGltfScene(sample("DamagedHelmet/glTF/DamagedHelmet.gltf"));
    CHECK(helmet.materials.at(0).kd > 0.05f);
    CHECK(helmet.materials.at(0).kd < 0.95f);
  }
}

TEST_SUITE("scene gltf invalid" * rt::test::needsShared()) {
  TEST_CASE(
      "every file of gltf-invalid loads or is rejected with one line, fast, without crashing") {
    const fs::path dir = assetDir("gltf-invalid");
    std::map<std::string, std::vector<std::string>> classes;
    size_t loaded = 0, rejected = 0;
    for (const fs::path& file : gltfFilesUnder(dir)) {
      std::string relative = fs::relative(file, dir).string();
      Outcome outcome = loadIsolated(file, 20);
      CHECK_MESSAGE(outcome.seconds < 10.0, relative);
      switch (outcome.kind) {
        case Outcome::Loaded:
          ++loaded;
          MESSAGE("[loaded]   " << relative << ": " << outcome.text);
          break;
        case Outcome::Rejected:
          ++rejected;
          MESSAGE("[rejected] " << relative << ": " << outcome.text);
          CHECK_MESSAGE(!contains(outcome.text, "\n"), "one line: " << outcome.text);
          CHECK_MESSAGE(outcome.text.rfind(file.string() + ": ", 0) == 0, outcome.text);
          classes[messageClass(outcome.text, file)].push_back(relative);
          break;
        case Outcome::OtherException:
          FAIL(relative << ": not an rt::Error: " << outcome.text);
          break;
        case Outcome::Crashed: FAIL(relative << ": crashed: " << outcome.text); break;
        case Outcome::TimedOut: FAIL(relative << ": did not finish in 20 s"); break;
      }
    }
    MESSAGE(loaded << " loaded, " << rejected << " rejected");
    for (const auto& [kind, files] : classes) {
      MESSAGE("rejected as '" << kind << "': " << files.size() << " file(s)");
    }
    CHECK(loaded + rejected > 40);
  }
}

TEST_SUITE("scene gltf render" * rt::test::needsShared()) {
  // Small renders on whatever Vulkan device the tests use (lavapipe in CI),
  // saved under the test output folder for looking at.
  TEST_CASE("sample models render to finite images that show the model") {
    const fs::path dir = assetDir("gltf/khronos-sample-assets");
    const std::vector<std::pair<std::string, std::string>> models = {
        {"Box/glTF-Binary/Box.glb", "gltf-box.png"},
        {"SimpleInstancing/glTF-Binary/SimpleInstancing.glb", "gltf-instancing.png"},
        {"NegativeScaleTest/glTF-Binary/NegativeScaleTest.glb", "gltf-negative-scale.png"},
        {"Duck/glTF-Binary/Duck.glb", "gltf-duck.png"},
    };
    rt::Renderer renderer(rt::test::gpu(), rt::test::shaderCompiler());
    for (const auto& entry : models) {
      // Named references, not a structured binding: clang 14 cannot capture
      // those in CAPTURE's lambda.
      const std::string& model = entry.first;
      const std::string& output = entry.second;
      CAPTURE(model);
      rt::Scene scene = rt::loadGltfScene(dir / model);
      rt::RenderOptions options;
      options.width = 160;
      options.height = 120;
      options.samplesPerPixel = 2;
      rt::ImageF image = renderer.render(scene, options);
      rt::test::checkNoValidationMessages();
      size_t differing = 0;
      bool allFinite = true;
      for (size_t i = 0; i < image.rgba.size(); i += 4) {
        for (int c = 0; c < 3; ++c) allFinite = allFinite && std::isfinite(image.rgba[i + c]);
        if (std::abs(image.rgba[i] - scene.backgroundColor.x) > 0.02f) ++differing;
      }
      CHECK(allFinite);
      CHECK(differing > image.rgba.size() / 4 / 20);  // the model covers some of the image
      rt::test::savePng(rt::toneMap(image, {}), output);
    }
  }
}
