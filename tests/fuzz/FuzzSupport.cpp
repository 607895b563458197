#include "FuzzSupport.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <glm/gtc/matrix_access.hpp>
#include <nlohmann/json.hpp>
#include <utility>
#include <variant>

#include "formats/gltf/GltfContext.hpp"

namespace rt::fuzz {

namespace fs = std::filesystem;

namespace {

// The loaders' own limit for an image side.
constexpr uint32_t kMaxImageSide = 16384;

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz finding: %s\n", what.c_str());
  std::abort();
}

std::vector<fs::path> scratchDirs;

void removeScratchDirs() {
  for (const fs::path& dir : scratchDirs) {
    std::error_code ignored;
    fs::remove_all(dir, ignored);
  }
}

bool isInside(const fs::path& path, const fs::path& root) {
  const auto [rootEnd, pathAt] = std::mismatch(root.begin(), root.end(), path.begin(), path.end());
  return rootEnd == root.end();
}

// Every string value anywhere in the document.
void collectStrings(const nlohmann::json& value, std::vector<std::string>& out) {
  if (value.is_string()) {
    out.push_back(value.get<std::string>());
  } else if (value.is_structured()) {
    for (const nlohmann::json& child : value) collectStrings(child, out);
  }
}

bool isSeedDocument(const fs::path& file) {
  const fs::path extension = file.extension();
  return extension == ".json" || extension == ".gltf";
}

// Links `target` at `link` unless something is there already (first seed wins).
void linkOnce(const fs::path& target, const fs::path& link) {
  std::error_code error;
  if (fs::exists(fs::symlink_status(link, error))) return;
  fs::create_directories(link.parent_path(), error);
  fs::create_symlink(target, link, error);
}

void linkReferencesOf(const fs::path& document, const fs::path& placeDir,
                      const fs::path& scratchRoot, uintmax_t maxBytes) {
  std::ifstream in(document);
  const nlohmann::json parsed = nlohmann::json::parse(in, nullptr, false);
  std::vector<std::string> strings;
  collectStrings(parsed, strings);
  const fs::path ownDir = document.parent_path();
  for (const std::string& text : strings) {
    if (text.empty() || text.size() > 512 || text.rfind("data:", 0) == 0) continue;
    for (const std::string& relative : {text, gltf::percentDecoded(text)}) {
      const fs::path written(relative);
      if (written.is_absolute()) continue;
      for (const auto& [base, place] :
           {std::pair{ownDir, placeDir}, std::pair{ownDir.parent_path(), placeDir.parent_path()}}) {
        const fs::path target = (base / written).lexically_normal();
        const fs::path link = (place / written).lexically_normal();
        std::error_code error;
        if (!fs::is_regular_file(target, error) || fs::file_size(target, error) > maxBytes)
          continue;
        if (isInside(link, scratchRoot)) linkOnce(fs::absolute(target), link);
        break;
      }
    }
  }
}

// Float directions and colours, double world positions and placements.
template <typename T>
bool finite(const glm::vec<3, T>& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

template <typename T>
bool finite(const glm::mat<4, 4, T>& m) {
  for (int column = 0; column < 4; ++column) {
    const glm::vec<4, T> c = glm::column(m, column);
    if (!finite(glm::vec<3, T>(c)) || !std::isfinite(c.w)) return false;
  }
  return true;
}

bool nonNegative(const glm::vec3& v) { return v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f; }

bool unitLength(const glm::vec3& v) { return std::abs(glm::length(v) - 1.0f) < 1e-3f; }

void checkCamera(const Camera& camera) {
  if (camera.width == 0 || camera.height == 0 || camera.width > kMaxImageSide ||
      camera.height > kMaxImageSide) {
    finding("camera image size out of range: " + std::to_string(camera.width) + "x" +
            std::to_string(camera.height));
  }
  if (!(camera.fovYDegrees > 0.0f && camera.fovYDegrees < 180.0f)) {
    finding("camera field of view out of (0, 180): " + std::to_string(camera.fovYDegrees));
  }
  if (!finite(camera.position) || !finite(camera.up) || !unitLength(camera.forward)) {
    finding("camera position, up or forward not finite (or forward not unit)");
  }
  if (!(camera.apertureRadius >= 0.0f) || !std::isfinite(camera.apertureRadius) ||
      !(camera.focusDistance > 0.0f) || !std::isfinite(camera.focusDistance)) {
    finding("camera lens values out of range");
  }
}

void checkMaterial(const Material& material, size_t textureCount) {
  const bool finiteWeights = std::isfinite(material.kd) && std::isfinite(material.ks) &&
                             std::isfinite(material.specularExponent) &&
                             std::isfinite(material.ior);
  if (!finiteWeights || !finite(material.diffuseColor) || !finite(material.specularColor)) {
    finding("material with a non-finite value");
  }
  for (int32_t texture : {material.diffuseTexture, material.normalTexture, material.glowTexture}) {
    if (texture < -1 || (texture >= 0 && size_t(texture) >= textureCount)) {
      finding("material texture index " + std::to_string(texture) + " out of range");
    }
  }
  if (!std::isfinite(material.normalScale)) finding("non-finite normal map scale");
  if (!finite(material.glow) || !nonNegative(material.glow)) finding("bad glow colour");
}

struct GeometryCheck {
  const Scene& scene;
  void operator()(const Sphere& s) const {
    if (!finite(s.center) || !(s.radius > 0.0f) || !std::isfinite(s.radius)) finding("bad sphere");
  }
  void operator()(const Triangle& t) const {
    if (!finite(t.v0) || !finite(t.v1) || !finite(t.v2)) finding("non-finite triangle");
  }
  void operator()(const Quad& q) const {
    if (!finite(q.v0) || !finite(q.v1) || !finite(q.v2) || !finite(q.v3)) finding("bad quad");
  }
  void operator()(const Cylinder& c) const {
    if (!finite(c.center) || !unitLength(c.axis) || !(c.radius > 0.0f) || !(c.halfHeight > 0.0f) ||
        !std::isfinite(c.radius) || !std::isfinite(c.halfHeight)) {
      finding("bad cylinder");
    }
  }
  void operator()(const MeshInstance& m) const {
    if (m.mesh >= scene.meshes.size()) finding("mesh instance of a mesh that does not exist");
    if (!finite(m.objectToWorld)) finding("non-finite mesh placement");
  }
};

}  // namespace

fs::path sharedDir() {
  std::error_code error;
  const fs::path dir = fs::path(RT_SHARED_DIR);
  return fs::is_directory(dir, error) ? fs::canonical(dir, error) : fs::path();
}

fs::path makeScratchDir(std::string_view purpose) {
  std::error_code error;
  fs::path base = fs::temp_directory_path(error);
  if (error) base = "/tmp";
  std::string pattern = (base / ("rt-fuzz-" + std::string(purpose) + "-XXXXXX")).string();
  if (!mkdtemp(pattern.data())) finding("cannot create a scratch folder in " + base.string());
  if (scratchDirs.empty()) std::atexit(removeScratchDirs);
  scratchDirs.push_back(fs::canonical(pattern));
  return scratchDirs.back();
}

void linkReferencedFiles(const std::vector<fs::path>& seedRoots, const fs::path& placeDir,
                         const fs::path& scratchRoot, uintmax_t maxBytes) {
  std::error_code error;
  fs::create_directories(placeDir, error);
  for (const fs::path& root : seedRoots) {
    if (!fs::is_directory(root, error)) continue;
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(root, error)) {
      if (entry.is_regular_file(error) && isSeedDocument(entry.path())) {
        linkReferencesOf(entry.path(), placeDir, scratchRoot, maxBytes);
      }
    }
  }
}

void writeInput(const fs::path& file, const uint8_t* bytes, size_t size) {
  std::FILE* stream = std::fopen(file.c_str(), "wb");
  if (!stream) finding("cannot write the input to " + file.string());
  const bool written = std::fwrite(bytes, 1, size, stream) == size;
  if (std::fclose(stream) != 0 || !written) finding("cannot write the input to " + file.string());
}

void checkErrorMessage(std::string_view message, std::string_view file) {
  if (message.find_first_of("\r\n") != std::string_view::npos) {
    finding("error message of more than one line: " + std::string(message));
  }
  if (message.substr(0, file.size()) != file) {
    finding("error message does not start with the file name '" + std::string(file) +
            "': " + std::string(message));
  }
}

void checkMesh(const TriangleMesh& mesh) {
  if (mesh.positions.empty() || mesh.faces.empty()) finding("mesh without vertices or faces");
  for (const glm::vec3& p : mesh.positions) {
    if (!finite(p)) finding("non-finite vertex position");
  }
  for (const glm::uvec3& face : mesh.faces) {
    if (face.x >= mesh.positions.size() || face.y >= mesh.positions.size() ||
        face.z >= mesh.positions.size()) {
      finding("face index out of range");
    }
  }
  if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size()) {
    finding("normal count differs from vertex count");
  }
  if (!mesh.uvs.empty() && mesh.uvs.size() != mesh.positions.size()) {
    finding("uv count differs from vertex count");
  }
  for (const glm::vec3& n : mesh.normals) {
    if (!unitLength(n)) finding("normal that is not unit length");
  }
  for (const glm::vec2& uv : mesh.uvs) {
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) finding("non-finite uv");
  }
  if (!mesh.colors.empty() && mesh.colors.size() != mesh.positions.size()) {
    finding("colour count differs from vertex count");
  }
  for (const glm::vec3& c : mesh.colors) {
    if (!(glm::all(glm::greaterThanEqual(c, glm::vec3(0.0f))) &&
          glm::all(glm::lessThanEqual(c, glm::vec3(1.0f))))) {
      finding("vertex colour outside [0, 1] or not finite");
    }
  }
}

void checkScene(const Scene& scene) {
  checkCamera(scene.camera);
  if (!finite(scene.backgroundColor) || !nonNegative(scene.backgroundColor)) {
    finding("bad background colour");
  }
  for (const PointLight& light : scene.pointLights) {
    if (!finite(light.position) || !finite(light.diffuseIntensity) ||
        !finite(light.specularIntensity) || !nonNegative(light.diffuseIntensity) ||
        !nonNegative(light.specularIntensity)) {
      finding("bad point light");
    }
  }
  for (const AreaLight& light : scene.areaLights) {
    if (light.shape >= scene.shapes.size()) finding("area light shape index out of range");
    if (!finite(light.diffuseIntensity) || !finite(light.specularIntensity) ||
        !nonNegative(light.diffuseIntensity) || !nonNegative(light.specularIntensity) ||
        light.samples == 0) {
      finding("bad area light");
    }
  }
  for (const Material& material : scene.materials) checkMaterial(material, scene.textures.size());
  for (const Shape& shape : scene.shapes) {
    if (shape.material >= scene.materials.size()) finding("shape material index out of range");
    std::visit(GeometryCheck{scene}, shape.geometry);
  }
  for (const TriangleMesh& mesh : scene.meshes) checkMesh(mesh);
  for (const Texture& texture : scene.textures) {
    const ImageRgba8& image = texture.image;
    if (image.width == 0 || image.height == 0 ||
        image.rgba.size() != size_t(image.width) * image.height * 4) {
      finding("texture whose pixel data does not match its size");
    }
  }
  for (const std::string& warning : scene.warnings) {
    if (warning.find_first_of("\r\n") != std::string::npos) {
      finding("warning of more than one line: " + warning);
    }
  }
}

std::filesystem::path prepareInputFile(std::string_view purpose,
                                       const std::filesystem::path& inputDir,
                                       const std::vector<std::string>& seedFolders,
                                       uintmax_t maxLinkedBytes, const std::string& fileName) {
  const std::filesystem::path root = makeScratchDir(purpose);
  const std::filesystem::path placeDir = root / inputDir;
  std::vector<std::filesystem::path> seedRoots;
  if (const std::filesystem::path shared = sharedDir(); !shared.empty()) {
    for (const std::string& folder : seedFolders) seedRoots.push_back(shared / folder);
  }
  linkReferencedFiles(seedRoots, placeDir, root, maxLinkedBytes);
  return placeDir / fileName;
}

}  // namespace rt::fuzz
